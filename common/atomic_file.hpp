#pragma once
// A file that appears under its name only when complete: written to "<path>.partial", renamed
// over <path> by commit(). Destroyed without commit() (an error, an exception), the partial file
// is removed, so a failed run never leaves a half-written output under the real name.

#include <cstdio>
#include <stdexcept>
#include <string>
#include <string_view>

namespace vcockpit {

class FileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class AtomicFile {
 public:
  explicit AtomicFile(const std::string& path);  // throws FileError naming the path
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::FILE* get() const { return file_; }
  // appends `text`; a failed write shows at commit()
  void write(std::string_view text);
  const std::string& path() const { return path_; }
  // flush, fsync, rename into place; throws FileError naming the path on failure
  void commit();

 private:
  std::string path_;
  std::string partial_path_;
  std::FILE* file_ = nullptr;
};

}  // namespace vcockpit
