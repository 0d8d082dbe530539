#include "model/import/isolated_reader.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string_view>
#include <vector>

namespace vcockpit::model {
namespace {

// The most a child may answer (a mesh with its images): past it the read is stopped.
constexpr std::size_t kMaxAnswerBytes = std::size_t{2} << 30;

// A mesh in the child's message: its source, vertices, triangles, normals, colours, counts,
// texture coordinates and images, each as a count and its raw bytes.
template <typename T>
void put(std::string& out, const std::vector<T>& v) {
  const uint64_t n = v.size();
  out.append(reinterpret_cast<const char*>(&n), sizeof n);
  if (n > 0) out.append(reinterpret_cast<const char*>(v.data()), n * sizeof(T));
}

void put(std::string& out, const std::string& s) {
  put(out, std::vector<char>(s.begin(), s.end()));
}

class Reader {
 public:
  explicit Reader(std::string_view bytes) : bytes_(bytes) {}
  template <typename T>
  bool get(std::vector<T>& v) {
    uint64_t n = 0;
    if (!raw(&n, sizeof n) || n > (bytes_.size() - at_) / sizeof(T)) return false;
    v.resize(n);
    return raw(v.data(), n * sizeof(T));
  }
  bool get(std::string& s) {
    std::vector<char> chars;
    if (!get(chars)) return false;
    s.assign(chars.begin(), chars.end());
    return true;
  }
  bool byte(char& c) { return raw(&c, 1); }
  bool done() const { return at_ == bytes_.size(); }

 private:
  bool raw(void* out, std::size_t n) {
    if (n > bytes_.size() - at_) return false;
    if (n == 0) return true;  // (an empty vector's data() may be null)
    std::memcpy(out, bytes_.data() + at_, n);
    at_ += n;
    return true;
  }
  std::string_view bytes_;
  std::size_t at_ = 0;
};

void put_mesh(std::string& out, const TriangleMesh& mesh) {
  put(out, mesh.source);
  put(out, mesh.vertices_m);
  put(out, mesh.triangles);
  put(out, mesh.normals);
  put(out, mesh.colors_rgba);
  put(out, std::vector<uint64_t>{mesh.degenerate_dropped, mesh.first_degenerate,
                                 mesh.textures_left_out, mesh.textures.size()});
  put(out, mesh.first_texture_left_out);
  put(out, mesh.uv);
  put(out, mesh.triangle_texture);
  for (const TextureImage& image : mesh.textures) {
    put(out, image.name);
    const TextureSampler& k = image.sampler;
    put(out, std::vector<uint32_t>{image.width, image.height, static_cast<uint32_t>(k.wrap_u),
                                   static_cast<uint32_t>(k.wrap_v),
                                   static_cast<uint32_t>(k.magnify),
                                   static_cast<uint32_t>(k.minify)});
    put(out, image.rgba);
  }
}

// The child's message: a status byte, 0 and the error's text when the file could not be read at
// all, or 1, the number of parts, and each part: a byte, 1 and its mesh or 0 and its error.
std::string encode(const std::function<std::vector<ModelPart>()>& read) {
  std::string out;
  try {
    const std::vector<ModelPart> parts = read();
    out.push_back(1);
    put(out, std::vector<uint64_t>{parts.size()});
    for (const ModelPart& part : parts) {
      if (part.mesh) {
        out.push_back(1);
        put_mesh(out, *part.mesh);
      } else {
        out.push_back(0);
        put(out, part.error);
      }
    }
  } catch (const std::exception& e) {
    out.assign(1, 0);
    put(out, std::string(e.what()));
  }
  return out;
}

void write_all(int fd, const std::string& bytes) {
  std::size_t at = 0;
  while (at < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + at, bytes.size() - at);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;
    at += static_cast<std::size_t>(n);
  }
}

int64_t now_ms() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return int64_t{ts.tv_sec} * 1000 + ts.tv_nsec / 1'000'000;
}

// The parent's side of one read: the pipe's end and the child, closed and reaped whatever happens.
class Child {
 public:
  Child(pid_t pid, int fd) : pid_(pid), fd_(fd) {}
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;
  ~Child() {
    if (fd_ >= 0) ::close(fd_);
    if (!reaped_) {
      ::kill(pid_, SIGKILL);
      wait();
    }
  }

  // Everything the child writes until it closes its end, or false at the deadline.
  bool too_large = false;  // read_all stopped at kMaxAnswerBytes

  bool read_all(std::string& answer, int64_t deadline_ms) {
    char buffer[1 << 16];
    for (;;) {
      const int64_t left_ms = deadline_ms - now_ms();
      if (left_ms <= 0) return false;
      if (answer.size() > kMaxAnswerBytes) {
        too_large = true;
        return false;
      }
      pollfd p{fd_, POLLIN, 0};
      const int ready = ::poll(&p, 1, static_cast<int>(left_ms));
      if (ready <= 0) continue;  // (EINTR, or the deadline checked above)
      const ssize_t n = ::read(fd_, buffer, sizeof buffer);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) return true;  // all said (or it died)
      answer.append(buffer, static_cast<std::size_t>(n));
    }
  }

  int wait() {
    int status = 0;
    while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
    reaped_ = true;
    return status;
  }

  void kill() { ::kill(pid_, SIGKILL); }

 private:
  pid_t pid_;
  int fd_;
  bool reaped_ = false;
};

TriangleMesh get_mesh(Reader& body, const MeshError& cut_short) {
  TriangleMesh mesh;
  std::vector<uint64_t> counts;
  if (!body.get(mesh.source) || !body.get(mesh.vertices_m) || !body.get(mesh.triangles) ||
      !body.get(mesh.normals) || !body.get(mesh.colors_rgba) || !body.get(counts) ||
      counts.size() != 4 || !body.get(mesh.first_texture_left_out) || !body.get(mesh.uv) ||
      !body.get(mesh.triangle_texture) || counts[3] > 4096)
    throw cut_short;
  mesh.degenerate_dropped = counts[0];
  mesh.first_degenerate = counts[1];
  mesh.textures_left_out = counts[2];
  mesh.textures.resize(counts[3]);
  for (TextureImage& image : mesh.textures) {
    std::vector<uint32_t> size;
    if (!body.get(image.name) || !body.get(size) || size.size() != 6 || !body.get(image.rgba) ||
        size[2] > 2 || size[3] > 2 || size[4] > 1 || size[5] > 1)
      throw cut_short;
    image.width = size[0];
    image.height = size[1];
    image.sampler = {static_cast<TextureWrap>(size[2]), static_cast<TextureWrap>(size[3]),
                     static_cast<TextureFilter>(size[4]), static_cast<TextureFilter>(size[5])};
  }
  check_mesh(mesh);  // what the child sent fits together, whatever the file did to it
  return mesh;
}

std::vector<ModelPart> decode(const std::string& answer, const std::string& what) {
  const MeshError cut_short(what + ": the model reader's answer was cut short");
  Reader body(std::string_view(answer).substr(1));
  if (answer[0] == 0) {
    std::string message;
    if (!body.get(message)) throw cut_short;
    throw MeshError(message);
  }
  std::vector<uint64_t> count;
  // (each part takes 9 bytes at least: its flag and a count; more parts than that is garbage)
  if (!body.get(count) || count.size() != 1 || count[0] > answer.size() / 9) throw cut_short;
  std::vector<ModelPart> parts(count[0]);
  for (ModelPart& part : parts) {
    char flag = 0;
    if (!body.byte(flag) || (flag != 0 && flag != 1)) throw cut_short;
    if (flag == 1) {
      part.mesh = get_mesh(body, cut_short);
    } else if (!body.get(part.error)) {
      throw cut_short;
    }
  }
  if (!body.done()) throw cut_short;
  return parts;
}

}  // namespace

std::vector<ModelPart> read_isolated_parts(const std::function<std::vector<ModelPart>()>& read,
                                          const std::string& what, int timeout_s) {
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0)
    throw MeshError(what + ": cannot read it apart (pipe: " + std::strerror(errno) + ")");
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    throw MeshError(what + ": cannot read it apart (fork: " + std::strerror(errno) + ")");
  }
  if (pid == 0) {  // the child: read, answer, and leave without the parent's exit handlers
    ::close(fds[0]);
    // gone with its parent; a crash is a plain death by signal (not the parent's crash
    // handlers: a sanitizer's report, a fuzzer's artifact); no more CPU than its time
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    for (int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT})
      ::signal(sig, SIG_DFL);
    const rlimit cpu{static_cast<rlim_t>(timeout_s), static_cast<rlim_t>(timeout_s) + 1};
    ::setrlimit(RLIMIT_CPU, &cpu);
    write_all(fds[1], encode(read));
    ::_exit(0);
  }
  ::close(fds[1]);
  Child child(pid, fds[0]);
  std::string answer;
  const bool answered = child.read_all(answer, now_ms() + int64_t{timeout_s} * 1000);
  if (!answered) child.kill();
  const int status = child.wait();
  if (child.too_large)
    throw MeshError(what + ": the model is larger than " + std::to_string(kMaxAnswerBytes >> 30) +
                    " GiB of triangles and images (stopped)");
  if (!answered || (WIFSIGNALED(status) && WTERMSIG(status) == SIGXCPU))
    throw MeshError(what + ": the model reader took more than " + std::to_string(timeout_s) +
                    " s on it (stopped)");
  if (WIFSIGNALED(status))
    throw MeshError(what + ": the model reader crashed on it (signal " +
                    std::to_string(WTERMSIG(status)) + "): a malformed file");
  if (answer.empty() || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw MeshError(what + ": the model reader failed on it (exit " +
                    std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) +
                    "): a malformed file");
  return decode(answer, what);
}

TriangleMesh read_isolated(const std::function<TriangleMesh()>& read, const std::string& what,
                           int timeout_s) {
  std::vector<ModelPart> parts = read_isolated_parts(
      [&] {
        std::vector<ModelPart> one(1);
        one[0].mesh = read();
        return one;
      },
      what, timeout_s);
  if (parts.size() != 1 || !parts[0].mesh)
    throw MeshError(what + ": the model reader's answer was cut short");
  return std::move(*parts[0].mesh);
}

}  // namespace vcockpit::model
