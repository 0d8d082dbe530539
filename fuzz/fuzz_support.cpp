#include "fuzz/fuzz_support.hpp"

#include <sys/mman.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#include "hand/config/hand_yaml.hpp"

namespace vcockpit::fuzz {

std::string config_dir() { return VCOCKPIT_CONFIG_DIR; }

const hand::HandModel& default_hand() {
  static const hand::HandModel kHand = load_hand_model(config_dir() + "/hand.yaml");
  return kHand;
}

void broken(const char* what) {
  std::fprintf(stderr, "fuzz: parser promise broken: %s\n", what);
  std::abort();
}

MemFile::MemFile(std::string_view bytes) {
  fd_ = memfd_create("vcockpit_fuzz", MFD_CLOEXEC);
  if (fd_ < 0) throw std::runtime_error("memfd_create failed");
  for (std::size_t done = 0; done < bytes.size();) {
    const ssize_t n = write(fd_, bytes.data() + done, bytes.size() - done);
    if (n <= 0) throw std::runtime_error("write to memfd failed");
    done += static_cast<std::size_t>(n);
  }
  path_ = "/proc/self/fd/" + std::to_string(fd_);
}

MemFile::~MemFile() { close(fd_); }

}  // namespace vcockpit::fuzz
