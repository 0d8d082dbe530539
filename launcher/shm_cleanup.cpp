#include "launcher/shm_cleanup.hpp"

#include <algorithm>
#include <filesystem>
#include <system_error>

#include "common/fast_dds_shm.hpp"

namespace vcockpit::rig {

namespace fs = std::filesystem;

std::vector<std::string> dev_shm_entries() {
  std::vector<std::string> out;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator("/dev/shm", ec)) out.push_back(e.path().filename());
  std::sort(out.begin(), out.end());
  return out;
}

// Fast DDS's shared-memory files that appeared during the run (a killed node leaves its own).
int remove_new_dds_shm(const std::vector<std::string>& before) {
  int removed = 0;
  for (const auto& name : dev_shm_entries()) {
    if (std::binary_search(before.begin(), before.end(), name)) continue;
    std::error_code ec;
    if (is_fast_dds_shm_name(name) && fs::remove(fs::path("/dev/shm") / name, ec)) ++removed;
  }
  return removed;
}

}  // namespace vcockpit::rig
