#pragma once
// What the fuzz targets share: the bundled configuration (loaded once per process) and a way to
// hand fuzz bytes to a loader that only takes a path.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "hand/hand_model.hpp"

namespace vcockpit::fuzz {

// config/ of the source tree (VCOCKPIT_CONFIG_DIR).
std::string config_dir();

// config/hand.yaml, loaded on first use.
const hand::HandModel& default_hand();

// A promise the parser made does not hold: reported and aborted, so libFuzzer keeps the input.
[[noreturn]] void broken(const char* what);
inline void require(bool ok, const char* what) {
  if (!ok) broken(what);
}

inline std::string_view as_text(const uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

// The bytes in an anonymous in-memory file, named by a path (/proc/self/fd/N) while it lives.
class MemFile {
 public:
  explicit MemFile(std::string_view bytes);
  ~MemFile();
  MemFile(const MemFile&) = delete;
  MemFile& operator=(const MemFile&) = delete;
  const std::string& path() const { return path_; }

 private:
  int fd_ = -1;
  std::string path_;
};

}  // namespace vcockpit::fuzz
