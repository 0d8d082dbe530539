#include "common/atomic_file.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace vcockpit {
namespace {

[[noreturn]] void io_fail(const std::string& path, const std::string& what) {
  throw FileError(path + ": " + what + ": " + std::strerror(errno));
}

}  // namespace

AtomicFile::AtomicFile(const std::string& path) : path_(path), partial_path_(path + ".partial") {
  file_ = std::fopen(partial_path_.c_str(), "w");
  if (!file_) io_fail(partial_path_, "cannot create");
}

AtomicFile::~AtomicFile() {
  if (file_) {
    std::fclose(file_);
    std::remove(partial_path_.c_str());
  }
}

void AtomicFile::write(std::string_view text) {
  if (!file_) throw FileError(path_ + ": already committed");
  std::fwrite(text.data(), 1, text.size(), file_);
}

void AtomicFile::commit() {
  if (!file_) throw FileError(path_ + ": already committed");
  const bool ok = std::fflush(file_) == 0 && fsync(fileno(file_)) == 0 && !std::ferror(file_);
  std::fclose(file_);
  file_ = nullptr;
  if (!ok) {
    std::remove(partial_path_.c_str());
    io_fail(partial_path_, "write failed");
  }
  if (std::rename(partial_path_.c_str(), path_.c_str()) != 0) {
    std::remove(partial_path_.c_str());
    io_fail(path_, "cannot rename into place");
  }
}

}  // namespace vcockpit
