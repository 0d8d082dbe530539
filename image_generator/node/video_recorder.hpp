#pragma once
// The run's video: H.264 in MP4, encoded by the ffmpeg program in a child process, off the render
// thread and at low CPU priority, so recording never takes time from rendering or the physics.
// The render thread only copies the frame into one of a few preallocated slots (never blocks:
// with every slot busy the frame is dropped and counted); a worker thread scales it, burns in the
// sim time, and pipes it to ffmpeg as raw RGB frames with timestamps (matroska_stream.hpp).
//
// Timeline: the video's nominal rate is the display's, and each frame is placed by the monotonic
// time it was finished, so the video plays in real time and lasts as long as the run. The first
// frame is at video period 0 at t0; a frame finished at t is at period
// k = llround((t - t0) * fps / 1e9). Periods with no frame of their own (render slower than fps,
// or frames dropped) keep the previous image on screen: nothing is encoded for them, so an
// encoder that falls behind never builds a backlog. A frame whose k is not past the last one
// written is skipped (render faster than fps). Frames dropped after the last one written (the
// encoder behind at the end) leave its image written once more at the last rendered frame's k:
// the video always lasts as long as the rendering did.

#include <sys/types.h>

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace vcockpit::image_generator {

enum class VideoView { kLeftEye, kSideBySide };

struct VideoOptions {
  std::string path;   // e.g. OUT/rig.mp4; written as path + ".partial", renamed on a clean finish
  double fps = 60.0;  // the display rate = the video's constant frame rate
  VideoView view = VideoView::kLeftEye;
  int scale_down = 2;               // box-filter factor applied before encoding (1 = full size)
  std::string ffmpeg = "ffmpeg";    // program (PATH lookup when it has no '/')
  int queue_frames = 3;             // preallocated slots between the render thread and the encoder
  int crf = 23;                     // x264 quality (lower is better and bigger)
  std::string preset = "ultrafast";  // x264 speed preset
  // finish() waits this long for the queue to drain and ffmpeg to write the file, then kills
  // ffmpeg and reports the video lost: the node's own stop must stay bounded (the launcher
  // kills a node still running 3 s after asking it to stop)
  double finish_timeout_s = 2.0;
};

class VideoRecorder {
 public:
  // Starts ffmpeg. Throws std::invalid_argument for bad options or sizes and std::runtime_error
  // naming the program (or the log file) if ffmpeg cannot be started. ffmpeg's stderr goes to
  // path + ".ffmpeg.log", removed on success.
  VideoRecorder(VideoOptions options, int eye_width_px, int height_px);
  ~VideoRecorder();  // finish() if not done
  VideoRecorder(const VideoRecorder&) = delete;
  VideoRecorder& operator=(const VideoRecorder&) = delete;

  // Render thread (one thread submits): copies the view's region of the side-by-side RGBA8
  // frame (2 * eye_width by height) into a free slot and returns true; a frame in the same video
  // frame as the last one taken is skipped without a copy (counted, true); false (counted as
  // dropped) when every slot is busy, ffmpeg has failed or finish() has begun. Never blocks on
  // the encoder. frame_end_ns: monotonic time the frame was finished (its place on the
  // timeline); sim_time_ns: burned into the top-left corner ("sim 12.345 s").
  bool submit(const uint8_t* side_by_side_rgba, int64_t frame_end_ns, int64_t sim_time_ns);
  // The same without the copy on the render thread: the slot keeps the frame's buffer (the
  // renderer reads its next frames into others, stereo_renderer.hpp) and the encoder thread cuts
  // the view out of it and lets it go.
  using SharedFrame = std::shared_ptr<const std::vector<uint8_t>>;
  bool submit(SharedFrame side_by_side_rgba, int64_t frame_end_ns, int64_t sim_time_ns);

  // Encodes what is queued, closes ffmpeg's input and waits for it to write the file. On success
  // renames path.partial to path and returns true. On failure (or when no frame was recorded)
  // removes the partial file and returns false; error() says why, with ffmpeg's exit status and
  // the last lines of its log (kept for a failed encode). Later calls return the same result.
  // Call from one thread; submits racing with it are dropped.
  bool finish();
  const std::string& error() const { return error_; }  // after finish()

  uint64_t submitted() const;  // every submit() call, dropped ones included
  uint64_t dropped() const;    // submits refused: no free slot (the encoder fell behind) or failed
  uint64_t video_frames() const { return video_frames_; }  // images in the video
  // display periods the previous image stays on for (slow render, dropped frames): the video
  // lasts video_frames() + repeated() periods
  uint64_t repeated() const { return repeated_; }
  uint64_t skipped() const { return skipped_; }    // two frames in one video frame (fast render)
  int width_px() const { return width_px_; }       // of the video
  int height_px() const { return height_px_; }

 private:
  struct Slot {
    std::vector<uint8_t> rgba;  // the view's region, full size
    SharedFrame frame;          // or the whole frame, the region still to be cut (worker)
    int64_t frame_end_ns = 0;
    int64_t sim_time_ns = 0;
    int64_t index = 0;  // its video frame
  };
  void work();
  bool submit_frame(const uint8_t* side_by_side_rgba, SharedFrame frame, int64_t frame_end_ns,
                    int64_t sim_time_ns);
  void cut_view(const uint8_t* side_by_side_rgba, Slot& slot) const;
  std::string start_ffmpeg();  // "" or why not
  void raise_priorities() const;
  bool wait_for_ffmpeg(int64_t deadline_ns, int& status) const;
  void encode(const Slot& slot);
  // the view's pixels (stride_px from row to row) -> rgb_ (scaled, cropped, labelled)
  void convert(const uint8_t* rgba, int stride_px, int64_t sim_time_ns);
  void write_frame(int64_t index);  // rgb_ at period index
  bool write_all(const uint8_t* data, std::size_t bytes);
  void hold_last_frame_until(int64_t end_index);
  void fail_writing(const std::string& why);
  std::string finish_error(const std::string& why, int status) const;

  VideoOptions options_;
  int eye_width_px_;
  int source_width_px_;  // of a slot
  int source_height_px_;
  int width_px_;  // of the video: scaled, then cropped to even sizes for yuv420p
  int height_px_;
  int label_scale_;
  std::string partial_path_;
  std::string log_path_;
  std::vector<std::string> argv_;

  std::vector<Slot> slots_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;     // worker: a slot was published, or stop
  std::condition_variable drained_;  // finish(): the worker has returned
  uint64_t head_ = 0;                // slots published by submit (ring index head_ % size)
  uint64_t tail_ = 0;                // slots released by the worker
  bool stopping_ = false;
  bool worker_done_ = false;
  std::atomic<pid_t> worker_tid_{0};  // for finish() to raise its priority again
  bool write_failed_ = false;
  std::string write_error_;
  uint64_t submitted_ = 0;
  uint64_t dropped_ = 0;
  std::atomic<uint64_t> video_frames_{0};
  std::atomic<uint64_t> repeated_{0};
  std::atomic<uint64_t> skipped_{0};

  // the submitting thread's: the timeline's start, the last video frame taken (under mutex_)
  bool have_submit_t0_ = false;
  int64_t submit_t0_ns_ = 0;
  int64_t last_submitted_index_ = -1;
  int64_t last_rendered_index_ = -1;  // of every frame submitted, the dropped ones too
  // set by the constructor; written to by the worker; closed by finish() after the join
  pid_t pid_ = -1;
  int pipe_fd_ = -1;
  // worker only (read by finish() after the join)
  int64_t last_index_ = -1;
  std::vector<uint8_t> scaled_;
  std::vector<uint8_t> rgb_;

  bool finished_ = false;
  bool ok_ = false;
  std::string error_;
  std::thread worker_;
};

}  // namespace vcockpit::image_generator
