#include "image_generator/node/video_recorder.hpp"

#include <fcntl.h>
#include <pthread.h>
#include <sched.h>
#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <system_error>
#include <utility>

#include "image_generator/node/matroska_stream.hpp"
#include "image_generator/render/image_scale.hpp"
#include "image_generator/render/png_writer.hpp"
#include "image_generator/render/text_overlay.hpp"

extern char** environ;

namespace vcockpit::image_generator {
namespace {

constexpr int kNiceIncrement = 10;
constexpr int kPipeBytes = 1 << 20;  // fewer wake-ups per frame than the default 64 KiB
constexpr int kLogLines = 4;         // of ffmpeg's log quoted in error()

// Below render and physics (nice and policy are per thread on Linux; tid 0: the calling thread).
// SCHED_IDLE runs only on CPU time nothing else wants: on two cores rendering and the physics take
// all of it, and even nice 19 would still take a share from them; starved, ffmpeg falls behind and
// frames are dropped and counted instead. Only ffmpeg gets it: a SCHED_IDLE thread of the node
// itself, on a busy machine, would hold up the node's death by kill -9 (or a crash) for seconds
// (a process is gone only when each of its threads has run to exit), and its restart with it.
enum class Priority { kNice, kIdle };
void lower_priority(pid_t tid_or_0, Priority priority) {
  const auto tid = static_cast<id_t>(tid_or_0 == 0 ? syscall(SYS_gettid) : tid_or_0);
  errno = 0;
  const int current = getpriority(PRIO_PROCESS, tid);
  if (errno != 0) return;
  setpriority(PRIO_PROCESS, tid, std::min(current + kNiceIncrement, 19));
  if (priority == Priority::kIdle) {  // the nice value stays, for a system that refuses the policy
    sched_param param{};
    param.sched_priority = 0;
    sched_setscheduler(static_cast<pid_t>(tid), SCHED_IDLE, &param);
  }
}

// A write to a pipe whose reader died raises SIGPIPE on the writing thread; blocked here, the
// write fails with EPIPE instead and the recorder reports it.
void block_sigpipe() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGPIPE);
  pthread_sigmask(SIG_BLOCK, &set, nullptr);
}

std::string format_number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

std::string describe_status(int status) {
  if (WIFEXITED(status)) return "exit status " + std::to_string(WEXITSTATUS(status));
  if (WIFSIGNALED(status)) return "killed by signal " + std::to_string(WTERMSIG(status));
  return "status " + std::to_string(status);
}

// The last lines of ffmpeg's log, joined with " | ".
std::string log_tail(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r' || text.back() == ' ')) {
    text.pop_back();
  }
  std::size_t start = text.size();
  for (int lines = 0; lines < kLogLines && start > 0; ++lines) {
    const std::size_t nl = start >= 2 ? text.rfind('\n', start - 2) : std::string::npos;
    start = nl == std::string::npos ? 0 : nl + 1;
  }
  std::string tail;
  for (std::size_t i = start; i < text.size(); ++i) {
    if (text[i] == '\n') {
      tail += " | ";
    } else if (text[i] != '\r') {
      tail += text[i];
    }
  }
  return tail;
}

int64_t steady_now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

}  // namespace

VideoRecorder::VideoRecorder(VideoOptions options, int eye_width_px, int height_px)
    : options_(std::move(options)), eye_width_px_(eye_width_px) {
  if (options_.path.empty()) throw std::invalid_argument("video: empty output path");
  const std::string what = "video " + options_.path + ": ";
  if (eye_width_px <= 0 || height_px <= 0) throw std::invalid_argument(what + "empty frame");
  if (!(options_.fps > 0.0) || !std::isfinite(options_.fps)) {
    throw std::invalid_argument(what + "fps must be positive");
  }
  if (options_.scale_down < 1) throw std::invalid_argument(what + "scale_down must be >= 1");
  if (options_.queue_frames < 1) throw std::invalid_argument(what + "queue_frames must be >= 1");
  if (!(options_.finish_timeout_s > 0.0) || !std::isfinite(options_.finish_timeout_s)) {
    throw std::invalid_argument(what + "finish_timeout_s must be positive");
  }
  source_width_px_ = options_.view == VideoView::kLeftEye ? eye_width_px : 2 * eye_width_px;
  source_height_px_ = height_px;
  // yuv420p halves chroma both ways: an odd last column or row is cropped
  width_px_ = (source_width_px_ / options_.scale_down) & ~1;
  height_px_ = (source_height_px_ / options_.scale_down) & ~1;
  if (width_px_ < 2 || height_px_ < 2) {
    throw std::invalid_argument(what + "frame too small for scale_down " +
                                std::to_string(options_.scale_down));
  }
  label_scale_ = std::max(2, height_px_ / 240);  // 18 px high on 360 rows, 27 px on 720
  partial_path_ = options_.path + ".partial";
  log_path_ = options_.path + ".ffmpeg.log";

  // clang-format off
  argv_ = {options_.ffmpeg, "-hide_banner", "-nostats", "-loglevel", "error", "-y",
           "-f", "matroska", "-i", "pipe:0",
           "-an", "-c:v", "libx264", "-preset", options_.preset,
           "-crf", std::to_string(options_.crf), "-pix_fmt", "yuv420p", "-threads", "1",
           // each frame keeps its timestamp (a multiple of the display period): no repeats
           "-fps_mode", "vfr", "-r", format_number(options_.fps),
           "-movflags", "+faststart", "-f", "mp4", partial_path_};
  // clang-format on

  slots_.resize(static_cast<std::size_t>(options_.queue_frames));
  const std::size_t slot_bytes =
      static_cast<std::size_t>(source_width_px_) * static_cast<std::size_t>(height_px) * 4;
  for (Slot& slot : slots_)
    slot.rgba.resize(slot_bytes);
  if (options_.scale_down > 1) {
    scaled_.resize(static_cast<std::size_t>(source_width_px_ / options_.scale_down) *
                   static_cast<std::size_t>(source_height_px_ / options_.scale_down) * 4);
  }
  rgb_.resize(static_cast<std::size_t>(width_px_) * static_cast<std::size_t>(height_px_) * 3);

  // started here, not on the low-priority worker: on a busy machine the node would wait for it
  const std::string start_error = start_ffmpeg();
  if (!start_error.empty()) {
    finished_ = true;
    std::error_code ignored;
    std::filesystem::remove(log_path_, ignored);
    throw std::runtime_error(what + start_error);
  }
  worker_ = std::thread([this] { work(); });
}

VideoRecorder::~VideoRecorder() {
  try {
    finish();
  } catch (...) {  // a destructor must not throw; error() would have said why
  }
}

bool VideoRecorder::submit(const uint8_t* side_by_side_rgba, int64_t frame_end_ns,
                           int64_t sim_time_ns) {
  return submit_frame(side_by_side_rgba, nullptr, frame_end_ns, sim_time_ns);
}

bool VideoRecorder::submit(SharedFrame side_by_side_rgba, int64_t frame_end_ns, int64_t sim_time_ns) {
  const uint8_t* pixels = side_by_side_rgba ? side_by_side_rgba->data() : nullptr;
  return submit_frame(pixels, std::move(side_by_side_rgba), frame_end_ns, sim_time_ns);
}

void VideoRecorder::cut_view(const uint8_t* side_by_side_rgba, Slot& slot) const {
  if (options_.view == VideoView::kLeftEye) {
    render::copy_eye(side_by_side_rgba, eye_width_px_, source_height_px_, render::Eye::kLeft,
                     slot.rgba);
  } else {
    std::memcpy(slot.rgba.data(), side_by_side_rgba, slot.rgba.size());
  }
}

bool VideoRecorder::submit_frame(const uint8_t* side_by_side_rgba, SharedFrame frame,
                                 int64_t frame_end_ns, int64_t sim_time_ns) {
  // the frame's place on the video's timeline; a frame in the same video frame as the last one
  // taken is not copied at all (rendering faster than the video's rate)
  if (!have_submit_t0_) {
    submit_t0_ns_ = frame_end_ns;
    have_submit_t0_ = true;
  }
  const int64_t index =
      std::llround(static_cast<double>(frame_end_ns - submit_t0_ns_) * options_.fps / 1e9);
  std::unique_lock<std::mutex> lock(mutex_);
  ++submitted_;
  if (side_by_side_rgba) last_rendered_index_ = std::max(last_rendered_index_, index);
  if (side_by_side_rgba && index <= last_submitted_index_) {
    ++skipped_;
    return true;
  }
  if (!side_by_side_rgba || stopping_ || write_failed_ || head_ - tail_ >= slots_.size()) {
    ++dropped_;
    return false;
  }
  // the worker never touches the slot at head_ until head_ moves past it, so copy unlocked
  Slot& slot = slots_[head_ % slots_.size()];
  lock.unlock();
  if (frame) {
    slot.frame = std::move(frame);  // cut by the worker
  } else {
    cut_view(side_by_side_rgba, slot);
  }
  slot.frame_end_ns = frame_end_ns;
  slot.sim_time_ns = sim_time_ns;
  slot.index = index;
  lock.lock();
  last_submitted_index_ = index;
  if (stopping_) {  // finish() began during the copy: the worker may be gone
    slot.frame.reset();
    ++dropped_;
    return false;
  }
  ++head_;
  lock.unlock();
  wake_.notify_one();
  return true;
}

uint64_t VideoRecorder::submitted() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return submitted_;
}

uint64_t VideoRecorder::dropped() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return dropped_;
}

std::string VideoRecorder::start_ffmpeg() {
  const int log_fd = open(log_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (log_fd < 0) return "cannot create " + log_path_ + ": " + std::strerror(errno);
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) {
    const std::string why = std::string("pipe: ") + std::strerror(errno);
    close(log_fd);
    return why;
  }
  std::vector<char*> argv;
  for (std::string& arg : argv_)
    argv.push_back(arg.data());
  argv.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fds[0], STDIN_FILENO);
  posix_spawn_file_actions_adddup2(&actions, log_fd, STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, log_fd, STDERR_FILENO);
  // Own process group: a Ctrl-C at the terminal reaches the node, which finishes the video
  // cleanly, and not ffmpeg, which would stop mid-stream. Default signals, whatever this
  // thread blocks or the process ignores.
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  posix_spawnattr_setflags(&attr,
                           POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
  posix_spawnattr_setpgroup(&attr, 0);
  sigset_t none;
  sigemptyset(&none);
  posix_spawnattr_setsigmask(&attr, &none);
  sigset_t defaults;
  sigemptyset(&defaults);
  for (int sig : {SIGPIPE, SIGINT, SIGTERM, SIGHUP})
    sigaddset(&defaults, sig);
  posix_spawnattr_setsigdefault(&attr, &defaults);

  const int rc = posix_spawnp(&pid_, argv[0], &actions, &attr, argv.data(), environ);
  posix_spawnattr_destroy(&attr);
  posix_spawn_file_actions_destroy(&actions);
  close(fds[0]);
  close(log_fd);
  if (rc != 0) {
    close(fds[1]);
    pid_ = -1;
    return "cannot start ffmpeg program '" + options_.ffmpeg + "': " + std::strerror(rc);
  }
  // lowered from here (glibc's posix_spawn takes no SCHED_IDLE): its first milliseconds, before
  // it reads a frame, run at this thread's priority
  lower_priority(pid_, Priority::kIdle);
  pipe_fd_ = fds[1];
  fcntl(pipe_fd_, F_SETPIPE_SZ, kPipeBytes);  // best effort: the default size works too
  return "";
}

void VideoRecorder::work() {
  worker_tid_ = static_cast<pid_t>(syscall(SYS_gettid));
  lower_priority(0, Priority::kNice);
  block_sigpipe();
  const std::vector<uint8_t> header = matroska_stream_header(width_px_, height_px_);
  write_all(header.data(), header.size());
  std::unique_lock<std::mutex> lock(mutex_);
  while (true) {
    wake_.wait(lock, [this] { return head_ != tail_ || stopping_; });
    if (head_ == tail_) {  // stopping, and everything queued is written
      const int64_t end_index = last_rendered_index_;
      const bool writing = !write_failed_;
      lock.unlock();
      if (writing) hold_last_frame_until(end_index);
      lock.lock();
      break;
    }
    Slot& slot = slots_[tail_ % slots_.size()];
    const bool writing = !write_failed_;
    lock.unlock();
    if (writing) encode(slot);  // after a failure the queue just drains
    slot.frame.reset();  // a frame handed over whole: the renderer may read into it again
    lock.lock();
    ++tail_;
  }
  worker_done_ = true;
  drained_.notify_all();
}

void VideoRecorder::encode(const Slot& slot) {
  const int64_t index = slot.index;
  if (index <= last_index_) {
    ++skipped_;
    return;
  }
  if (slot.frame) {  // the view straight from the frame it is in: no copy of it first
    convert(slot.frame->data(), 2 * eye_width_px_, slot.sim_time_ns);
  } else {
    convert(slot.rgba.data(), source_width_px_, slot.sim_time_ns);
  }
  write_frame(index);
}

void VideoRecorder::hold_last_frame_until(int64_t end_index) {
  // frames dropped at the end (the encoder behind): the last image once more at the last
  // rendered frame's period, so the video still lasts as long as the run
  if (last_index_ >= 0 && last_index_ < end_index) write_frame(end_index);
}

void VideoRecorder::write_frame(int64_t index) {
  const int64_t timestamp_us = std::llround(static_cast<double>(index) * 1e6 / options_.fps);
  const auto prefix = matroska_frame_prefix(timestamp_us, rgb_.size());
  if (!write_all(prefix.data(), prefix.size()) || !write_all(rgb_.data(), rgb_.size())) return;
  if (last_index_ >= 0) repeated_ += static_cast<uint64_t>(index - last_index_ - 1);
  last_index_ = index;
  ++video_frames_;
}

void VideoRecorder::convert(const uint8_t* rgba, int stride_px, int64_t sim_time_ns) {
  int rgba_width = stride_px;
  if (options_.scale_down > 1) {
    render::downscale_rgba(rgba, source_width_px_, source_height_px_, options_.scale_down, scaled_,
                           stride_px);
    rgba = scaled_.data();
    rgba_width = source_width_px_ / options_.scale_down;
  }
  render::rgba_to_rgb(rgba, rgba_width, width_px_, height_px_, rgb_.data());
  char label[48];
  std::snprintf(label, sizeof label, "sim %.3f s", static_cast<double>(sim_time_ns) * 1e-9);
  render::draw_text(rgb_.data(), width_px_, height_px_, 3, label_scale_, label_scale_, label_scale_,
                    label);
}

bool VideoRecorder::write_all(const uint8_t* data, std::size_t left) {
  while (left > 0) {
    const ssize_t n = write(pipe_fd_, data, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      fail_writing(errno == EPIPE ? std::string("ffmpeg stopped reading its input")
                                  : std::string("writing to ffmpeg: ") + std::strerror(errno));
      return false;
    }
    data += n;
    left -= static_cast<std::size_t>(n);
  }
  return true;
}

void VideoRecorder::fail_writing(const std::string& why) {
  std::lock_guard<std::mutex> lock(mutex_);
  write_failed_ = true;
  write_error_ = why;
}

std::string VideoRecorder::finish_error(const std::string& why, int status) const {
  std::string text = "video " + options_.path + ": " + why;
  if (status >= 0) text += "; ffmpeg (" + options_.ffmpeg + ") " + describe_status(status);
  const std::string tail = log_tail(log_path_);
  if (!tail.empty()) text += "; its log (" + log_path_ + "): " + tail;
  return text;
}

void VideoRecorder::raise_priorities() const {
  errno = 0;
  const int own_nice = getpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)));
  if (errno != 0) return;
  sched_param normal{};
  normal.sched_priority = 0;
  for (const pid_t tid : {worker_tid_.load(), pid_}) {
    if (tid <= 0) continue;
    // refused without CAP_SYS_NICE (or RLIMIT_NICE): finish_timeout_s still bounds the wait
    sched_setscheduler(tid, SCHED_OTHER, &normal);
    setpriority(PRIO_PROCESS, static_cast<id_t>(tid), own_nice);
  }
}

bool VideoRecorder::wait_for_ffmpeg(int64_t deadline_ns, int& status) const {
  while (true) {
    int raw = 0;
    const pid_t r = waitpid(pid_, &raw, WNOHANG);
    if (r == pid_) {
      status = raw;
      return true;
    }
    if (r < 0 && errno != EINTR) return true;  // status stays lost
    if (steady_now_ns() >= deadline_ns) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

bool VideoRecorder::finish() {
  if (finished_) return ok_;
  finished_ = true;
  const int64_t deadline_ns =
      steady_now_ns() + static_cast<int64_t>(std::llround(options_.finish_timeout_s * 1e9));
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  // Low priority kept the encoder from taking time from rendering during the run; now the queued
  // frames and ffmpeg's last ones stand between the node and its exit, and on a busy machine a
  // SCHED_IDLE process may not run for seconds.
  raise_priorities();
  bool timed_out = false;
  {
    std::unique_lock<std::mutex> lock(mutex_);
    const auto deadline = std::chrono::steady_clock::time_point(std::chrono::nanoseconds(deadline_ns));
    timed_out = !drained_.wait_until(lock, deadline, [this] { return worker_done_; });
  }
  // a killed ffmpeg also frees a worker blocked writing into a full pipe (EPIPE)
  if (timed_out && pid_ > 0) kill(pid_, SIGKILL);
  worker_.join();
  if (pipe_fd_ >= 0) {
    close(pipe_fd_);  // end of input: ffmpeg flushes the encoder and writes the index
    pipe_fd_ = -1;
  }
  int status = -1;
  if (pid_ > 0) {
    if (!timed_out && !wait_for_ffmpeg(deadline_ns, status)) {
      timed_out = true;
      kill(pid_, SIGKILL);
    }
    if (timed_out) {
      int raw = 0;
      pid_t r;
      while ((r = waitpid(pid_, &raw, 0)) < 0 && errno == EINTR) {
      }
      if (r == pid_) status = raw;
    }
    pid_ = -1;
  }

  std::error_code ignored;
  std::string why;
  if (timed_out) {
    char text[96];
    std::snprintf(text, sizeof text, "not finished %.1f s after the run's end: ffmpeg was killed",
                  options_.finish_timeout_s);
    why = text;
  } else if (write_failed_) {
    why = write_error_;
  } else if (video_frames_ == 0) {
    why = "no frames were recorded";
  } else if (status < 0) {
    why = "ffmpeg's exit status was lost";
  } else if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    why = "ffmpeg failed";
  }
  if (why.empty()) {
    std::error_code renamed;
    std::filesystem::rename(partial_path_, options_.path, renamed);
    if (renamed) why = "cannot rename " + partial_path_ + ": " + renamed.message();
  }
  if (!why.empty()) {
    const bool nothing_recorded = video_frames_ == 0 && !write_failed_;
    error_ = finish_error(why, nothing_recorded ? -1 : status);
    std::filesystem::remove(partial_path_, ignored);
    // the log stays when it says something about the failure
    if (nothing_recorded || std::filesystem::file_size(log_path_, ignored) == 0) {
      std::filesystem::remove(log_path_, ignored);
    }
    return ok_ = false;
  }
  std::filesystem::remove(log_path_, ignored);
  return ok_ = true;
}

}  // namespace vcockpit::image_generator
