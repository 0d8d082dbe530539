#include "launcher/shm_cleanup.hpp"

#include <algorithm>
#include <filesystem>
#include <system_error>

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
    const bool dds = name.rfind("fastrtps_", 0) == 0 || name.rfind("sem.fastrtps_", 0) == 0 ||
                     name.rfind("fast_datasharing_", 0) == 0 ||
                     name.rfind("sem.fast_datasharing_", 0) == 0;
    std::error_code ec;
    if (dds && fs::remove(fs::path("/dev/shm") / name, ec)) ++removed;
  }
  return removed;
}

}  // namespace vcockpit::rig
