// The run's video: the text overlay, the in-memory PNG and the box-filter downscale, then
// VideoRecorder against the real ffmpeg (frames counted back with ffprobe): one video frame per
// display period, the previous image held when the render is slower (no frame encoded for it,
// however long the gap), skips when two frames share a period, the
// view cut and the label in the picture, failures reported with no file left, a full queue
// dropping frames without blocking, no allocation per frame, and ffmpeg at low priority.

#include "image_generator/node/video_recorder.hpp"

#include <gtest/gtest.h>
#include <sched.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "image_generator/render/image_scale.hpp"
#include "image_generator/render/png_writer.hpp"
#include "image_generator/render/text_overlay.hpp"
#include "tests/support/allocation_counter.hpp"
#include "tests/support/png_read.hpp"
#include "tests/support/process.hpp"

namespace vcockpit {
namespace {
namespace fs = std::filesystem;

// ---- text overlay ----

std::vector<uint8_t> filled(int width, int height, int channels, uint8_t value) {
  return std::vector<uint8_t>(static_cast<std::size_t>(width * height * channels), value);
}

TEST(TextOverlay, LightGlyphsOnADarkBoxAndNothingOutsideIt) {
  for (int channels : {3, 4}) {
    const int width = 200;
    const int height = 40;
    const std::vector<uint8_t> before = filled(width, height, channels, 100);
    std::vector<uint8_t> image = before;
    render::draw_text(image.data(), width, height, channels, 7, 5, 2, "sim 12.345 s");
    const render::TextBox box = render::text_box(7, 5, 2, "sim 12.345 s");
    ASSERT_LE(box.x + box.width, width);
    ASSERT_LE(box.y + box.height, height);
    EXPECT_EQ(box.height, 9 * 2);
    int white = 0;
    int dark = 0;
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x < width; ++x) {
        const std::size_t i = static_cast<std::size_t>((y * width + x) * channels);
        const bool inside =
            x >= box.x && x < box.x + box.width && y >= box.y && y < box.y + box.height;
        if (channels == 4) {
          ASSERT_EQ(image[i + 3], 100) << "alpha is left alone";
        }
        if (!inside) {
          for (int ch = 0; ch < channels; ++ch)
            ASSERT_EQ(image[i + ch], before[i + ch]);
          continue;
        }
        if (image[i] == 255 && image[i + 1] == 255 && image[i + 2] == 255) {
          ++white;
        } else {
          ASSERT_EQ(image[i], 40) << "the box darkens to 40% at " << x << "," << y;
          ++dark;
        }
      }
    }
    EXPECT_GT(white, 100) << channels << " channels";
    EXPECT_GT(dark, white);
  }
}

TEST(TextOverlay, GlyphShapeAtScaleOne) {
  // '1' of the 5x7 font, inside a one-pixel margin
  const char* expected[] = {".......", "...#...", "..##...", "...#...", "...#...",
                            "...#...", "...#...", "..###..", "......."};
  std::vector<uint8_t> image = filled(7, 9, 3, 0);
  render::draw_text(image.data(), 7, 9, 3, 0, 0, 1, "1");
  for (int y = 0; y < 9; ++y) {
    for (int x = 0; x < 7; ++x) {
      const bool lit = image[static_cast<std::size_t>((y * 7 + x) * 3)] == 255;
      EXPECT_EQ(lit, expected[y][x] == '#') << x << "," << y;
    }
  }
  std::vector<uint8_t> unknown = filled(7, 9, 3, 0);
  std::vector<uint8_t> question = filled(7, 9, 3, 0);
  render::draw_text(unknown.data(), 7, 9, 3, 0, 0, 1, "\x01");
  render::draw_text(question.data(), 7, 9, 3, 0, 0, 1, "?");
  EXPECT_EQ(unknown, question) << "characters without a glyph show as '?'";
}

TEST(TextOverlay, ClippedAtTheImageEdges) {
  const int width = 20;
  const int height = 10;
  const std::vector<uint8_t> before = filled(width, height, 4, 100);
  std::vector<uint8_t> image = before;
  render::draw_text(image.data(), width, height, 4, -8, 4, 3, "sim 1.000 s");
  for (std::size_t i = 0; i < static_cast<std::size_t>(4 * width * 4); ++i) {
    ASSERT_EQ(image[i], before[i]) << "rows above the box are untouched";
  }
  EXPECT_NE(image, before);
}

// ---- PNG in memory, downscale ----

uint32_t big_endian(const std::vector<uint8_t>& bytes, std::size_t at) {
  return uint32_t{bytes[at]} << 24 | uint32_t{bytes[at + 1]} << 16 | uint32_t{bytes[at + 2]} << 8 |
         bytes[at + 3];
}

TEST(EncodePng, SignatureSizeAndTheSameBytesAsTheFile) {
  const int width = 37;
  const int height = 21;
  std::vector<uint8_t> rgba(static_cast<std::size_t>(width * height * 4));
  for (std::size_t i = 0; i < rgba.size(); ++i)
    rgba[i] = static_cast<uint8_t>(i * 7);
  const std::vector<uint8_t> png = render::encode_png(rgba.data(), width, height);
  ASSERT_GT(png.size(), 33u);
  const std::vector<uint8_t> signature = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  EXPECT_TRUE(std::equal(signature.begin(), signature.end(), png.begin()));
  EXPECT_EQ(std::string(png.begin() + 12, png.begin() + 16), "IHDR");
  EXPECT_EQ(big_endian(png, 16), uint32_t{width});
  EXPECT_EQ(big_endian(png, 20), uint32_t{height});

  const std::string path = test::make_temp_dir("encode_png") + "/same.png";
  render::write_png(path, rgba.data(), width, height);
  std::ifstream in(path, std::ios::binary);
  const std::vector<uint8_t> file((std::istreambuf_iterator<char>(in)),
                                  std::istreambuf_iterator<char>());
  EXPECT_EQ(file, png) << "write_png and encode_png share one encoder";
  EXPECT_THROW(render::encode_png(rgba.data(), 0, height), std::invalid_argument);
  EXPECT_THROW(render::encode_png(rgba.data(), width, height, 10), std::invalid_argument);
}

TEST(DownscaleRgba, AveragesEachBlockRounded) {
  // 4x2 -> 2x1: the left block's four pixels, then the right block's
  const std::vector<uint8_t> src = {
      0, 10, 255, 1, 1, 20, 255, 2, 50, 0, 0, 0, 50, 0, 0, 0,  // row 0
      2, 30, 255, 3, 2, 40, 254, 3, 50, 0, 0, 0, 51, 0, 0, 3,  // row 1
  };
  std::vector<uint8_t> out;
  render::downscale_rgba(src.data(), 4, 2, 2, out);
  // (0+1+2+2+2)/4 = 1.25 -> 1; (10+20+30+40)/4 = 25; (1019+2)/4 -> 255; (9+2)/4 -> 2
  // (201+2)/4 -> 50; alpha (3+2)/4 -> 1
  EXPECT_EQ(out, (std::vector<uint8_t>{1, 25, 255, 2, 50, 0, 0, 1}));

  // factor 3 on 7x4: 2x1, the odd column and row dropped
  std::vector<uint8_t> wide(7 * 4 * 4);
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 7; ++x) {
      for (int ch = 0; ch < 4; ++ch)
        wide[static_cast<std::size_t>((y * 7 + x) * 4 + ch)] = static_cast<uint8_t>(x * 10 + y);
    }
  }
  render::downscale_rgba(wide.data(), 7, 4, 3, out);
  ASSERT_EQ(out.size(), 2u * 1u * 4u);
  EXPECT_EQ(out[0], 11);  // x 0..2, y 0..2: 10 + 1
  EXPECT_EQ(out[4], 41);  // x 3..5: 40 + 1
  EXPECT_THROW(render::downscale_rgba(wide.data(), 7, 4, 0, out), std::invalid_argument);
  EXPECT_THROW(render::downscale_rgba(wide.data(), 7, 4, 5, out), std::invalid_argument);
}

// ---- VideoRecorder ----

using image_generator::VideoOptions;
using image_generator::VideoRecorder;
using image_generator::VideoView;

bool have_ffmpeg() {
  return access("/usr/bin/ffmpeg", X_OK) == 0 && access("/usr/bin/ffprobe", X_OK) == 0;
}

#define SKIP_WITHOUT_FFMPEG()                                                          \
  do {                                                                                 \
    if (!have_ffmpeg()) GTEST_SKIP() << "/usr/bin/ffmpeg or ffprobe is not installed"; \
  } while (false)

std::string run(const std::string& command) {
  std::string out;
  if (std::FILE* pipe = popen(command.c_str(), "r")) {
    char buf[256];
    while (std::fgets(buf, sizeof buf, pipe))
      out += buf;
    pclose(pipe);
  }
  return out;
}

struct Probe {
  int width = 0;
  int height = 0;
  std::string rate;
  double duration_s = -1;
  int frames = -1;
};

// ffprobe prints the fields in its own order: width,height,r_frame_rate,duration,nb_read_frames
Probe probe(const std::string& path) {
  std::string line =
      run("ffprobe -v error -count_frames -select_streams v:0 -show_entries "
          "stream=nb_read_frames,width,height,r_frame_rate,duration -of csv=p=0 '" +
          path + "'");
  for (char& c : line) {
    if (c == ',') c = ' ';
  }
  Probe p;
  std::istringstream(line) >> p.width >> p.height >> p.rate >> p.duration_s >> p.frames;
  return p;
}

std::vector<std::string> files_in(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir))
    names.push_back(entry.path().filename());
  return names;
}

// A side-by-side frame: left eye red, right eye blue, and unless i < 0 a white bar moving with i
// so frames differ.
std::vector<uint8_t> stereo_frame(int eye_width, int height, int i) {
  std::vector<uint8_t> rgba(static_cast<std::size_t>(2 * eye_width * height * 4));
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < 2 * eye_width; ++x) {
      uint8_t* p = &rgba[static_cast<std::size_t>((y * 2 * eye_width + x) * 4)];
      const bool left = x < eye_width;
      const bool bar = i >= 0 && (x % eye_width) / 4 == i % (eye_width / 4);
      p[0] = bar ? 255 : left ? 200 : 0;
      p[1] = bar ? 255 : 0;
      p[2] = bar ? 255 : left ? 0 : 200;
      p[3] = 255;
    }
  }
  return rgba;
}

int64_t frame_time_ns(double fps, double periods) {
  return 1'000'000'000'000 + std::llround(periods * 1e9 / fps);
}

// Polls until done() or 10 s have passed; false on the timeout.
template <typename Done>
bool wait_for(Done done) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (!done()) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  return true;
}

struct Recording {
  std::string dir;
  VideoOptions options;
};

Recording recording(const std::string& name) {
  Recording r;
  r.dir = test::make_temp_dir("video_recorder");
  r.options.path = r.dir + "/" + name;
  r.options.scale_down = 1;
  // a loaded machine (the sanitizer builds beside it) can take ffmpeg over the rig's 2 s to end:
  // a test that expects a finished video waits as long as it takes, and the one that tests the
  // bound sets its own
  r.options.finish_timeout_s = 60.0;
  return r;
}

TEST(VideoRecorder, OneVideoFramePerDisplayPeriod) {
  SKIP_WITHOUT_FFMPEG();
  Recording r = recording("rig.mp4");
  const int n = 30;
  r.options.queue_frames = n;  // room for all: none dropped however slow the encoder
  VideoRecorder video(r.options, 96, 64);
  const std::vector<uint8_t> frame = stereo_frame(96, 64, 0);
  for (int i = 0; i < n; ++i) {
    ASSERT_TRUE(video.submit(frame.data(), frame_time_ns(60.0, i), i * 16'666'667));
  }
  ASSERT_TRUE(video.finish()) << video.error();
  EXPECT_EQ(video.submitted(), uint64_t{n});
  EXPECT_EQ(video.dropped(), 0u);
  EXPECT_EQ(video.video_frames(), uint64_t{n});
  EXPECT_EQ(video.repeated(), 0u);
  EXPECT_EQ(video.skipped(), 0u);
  EXPECT_EQ(files_in(r.dir), std::vector<std::string>{"rig.mp4"}) << "no .partial, no log";
  const Probe p = probe(r.options.path);
  EXPECT_EQ(p.frames, n);
  EXPECT_NEAR(p.duration_s, n / 60.0, 1e-3);
  EXPECT_EQ(p.width, 96);
  EXPECT_EQ(p.height, 64);
  EXPECT_EQ(p.rate, "60/1");
}

// A shared frame is not copied on the submitting thread: the slot keeps the buffer until the
// encoder has cut its view, then lets it go; the video is the same as from copies.
TEST(VideoRecorder, SharedFramesAreKeptUntilEncodedThenLetGo) {
  SKIP_WITHOUT_FFMPEG();
  Recording r = recording("shared.mp4");
  const int n = 12;
  r.options.queue_frames = n;
  VideoRecorder video(r.options, 96, 64);
  std::vector<VideoRecorder::SharedFrame> frames;
  for (int i = 0; i < n; ++i) {
    frames.push_back(std::make_shared<const std::vector<uint8_t>>(stereo_frame(96, 64, i)));
    ASSERT_TRUE(video.submit(frames.back(), frame_time_ns(60.0, i), i * 16'666'667));
  }
  ASSERT_TRUE(video.finish()) << video.error();
  for (const auto& f : frames) EXPECT_EQ(f.use_count(), 1) << "every buffer let go";
  EXPECT_EQ(video.video_frames(), uint64_t{n});
  EXPECT_EQ(probe(r.options.path).frames, n);
  EXPECT_FALSE(video.submit(VideoRecorder::SharedFrame{}, frame_time_ns(60.0, n), 0))
      << "a missing frame is refused";
}

TEST(VideoRecorder, SlowerRenderHoldsEachFrameToKeepRealTime) {
  SKIP_WITHOUT_FFMPEG();
  Recording r = recording("half_rate.mp4");
  const int n = 15;
  r.options.queue_frames = n;
  VideoRecorder video(r.options, 96, 64);
  for (int i = 0; i < n; ++i) {
    const std::vector<uint8_t> frame = stereo_frame(96, 64, i);
    ASSERT_TRUE(video.submit(frame.data(), frame_time_ns(60.0, 2 * i), 0));
  }
  ASSERT_TRUE(video.finish()) << video.error();
  EXPECT_EQ(video.video_frames(), uint64_t{n}) << "one image per rendered frame";
  EXPECT_EQ(video.repeated(), uint64_t{n - 1}) << "each held for one more period";
  const Probe p = probe(r.options.path);
  EXPECT_EQ(p.frames, n);
  EXPECT_NEAR(p.duration_s, (2 * n - 1) / 60.0, 1e-3) << "lasts as long as the run: nothing padded";
}

// A long gap (a stalled renderer, or a busy machine on which the encoder got no CPU) costs the
// encoder nothing: the previous image stays on, no frame is encoded for the missing periods, and
// finish() is quick. Repeating the image for every period instead, a minute at 90 Hz took ffmpeg
// about 9 s, past the node's bounded stop, and the video was lost.
TEST(VideoRecorder, ALongGapHoldsTheImageWithoutEncodingIt) {
  SKIP_WITHOUT_FFMPEG();
  Recording r = recording("gap.mp4");
  r.options.fps = 90.0;
  VideoRecorder video(r.options, 320, 180);
  const int gap_periods = 90 * 60;
  for (int period : {0, 1, gap_periods}) {
    const std::vector<uint8_t> frame = stereo_frame(320, 180, period);
    ASSERT_TRUE(video.submit(frame.data(), frame_time_ns(90.0, period), 0));
    ASSERT_TRUE(wait_for([&] { return video.video_frames() + video.dropped() == video.submitted(); }));
  }
  const auto start = std::chrono::steady_clock::now();
  ASSERT_TRUE(video.finish()) << video.error();
  const double finish_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(video.video_frames(), 3u);
  EXPECT_EQ(video.repeated(), uint64_t{gap_periods - 2});
  const Probe p = probe(r.options.path);
  EXPECT_EQ(p.frames, 3);
  EXPECT_NEAR(p.duration_s, (gap_periods + 1) / 90.0, 1e-3);
  EXPECT_LT(finish_s, r.options.finish_timeout_s) << "nothing left to encode but three frames";
  // (the three frames, not the gap's 5,400 periods, are what was encoded: the counts above)
}

TEST(VideoRecorder, TwoFramesInOneDisplayPeriodSkipTheSecond) {
  SKIP_WITHOUT_FFMPEG();
  Recording r = recording("fast.mp4");
  VideoRecorder video(r.options, 96, 64);
  const std::vector<uint8_t> frame = stereo_frame(96, 64, 0);
  // periods 0, 1, 1.3 (rounds to 1: skipped), 1.6 (rounds to 2), 3
  for (double at : {0.0, 1.0, 1.3, 1.6, 3.0}) {
    ASSERT_TRUE(video.submit(frame.data(), frame_time_ns(60.0, at), 0));
    ASSERT_TRUE(wait_for([&] {
      return video.video_frames() + video.skipped() == video.submitted();
    })) << "one at a time";
  }
  ASSERT_TRUE(video.finish()) << video.error();
  EXPECT_EQ(video.skipped(), 1u);
  EXPECT_EQ(video.repeated(), 0u);
  EXPECT_EQ(video.video_frames(), 4u);
  EXPECT_EQ(probe(r.options.path).frames, 4);
}

TEST(VideoRecorder, OddScaledSizeIsCroppedToEven) {
  SKIP_WITHOUT_FFMPEG();
  Recording r = recording("odd.mp4");
  r.options.view = VideoView::kSideBySide;
  r.options.scale_down = 2;
  r.options.fps = 72.0;
  VideoRecorder video(r.options, 81, 94);  // 162x94 -> 81x47 -> 80x46
  EXPECT_EQ(video.width_px(), 80);
  EXPECT_EQ(video.height_px(), 46);
  const std::vector<uint8_t> frame = stereo_frame(81, 94, 0);
  for (int i = 0; i < 3; ++i)
    ASSERT_TRUE(video.submit(frame.data(), frame_time_ns(72.0, i), 0));
  ASSERT_TRUE(video.finish()) << video.error();
  const Probe p = probe(r.options.path);
  EXPECT_EQ(p.width, 80);
  EXPECT_EQ(p.height, 46);
  EXPECT_EQ(p.rate, "72/1");
}

// The first video frame as RGBA, decoded by ffmpeg into a PNG.
test::RgbaImage first_frame(const std::string& video, const std::string& png) {
  run("ffmpeg -v error -i '" + video + "' -frames:v 1 -y '" + png + "'");
  test::RgbaImage image;
  EXPECT_TRUE(test::read_png(png, image)) << png;
  return image;
}

TEST(VideoRecorder, TheViewIsCutAndTheSimTimeBurnedIn) {
  SKIP_WITHOUT_FFMPEG();
  for (VideoView view : {VideoView::kLeftEye, VideoView::kSideBySide}) {
    Recording r = recording(view == VideoView::kLeftEye ? "left.mp4" : "both.mp4");
    r.options.view = view;
    VideoRecorder video(r.options, 160, 120);
    const std::vector<uint8_t> frame = stereo_frame(160, 120, -1);
    ASSERT_TRUE(video.submit(frame.data(), frame_time_ns(60.0, 0), 12'345'000'000));
    ASSERT_TRUE(video.finish()) << video.error();
    const test::RgbaImage image = first_frame(r.options.path, r.dir + "/first.png");
    ASSERT_EQ(image.width, view == VideoView::kLeftEye ? 160 : 320);
    ASSERT_EQ(image.height, 120);
    const auto left = image.at(100, 80);
    EXPECT_GT(left[0], 150);
    EXPECT_LT(left[2], 60) << "the left eye is red";
    const auto right = image.at(image.width - 20, 80);
    if (view == VideoView::kLeftEye) {
      EXPECT_GT(right[0], 150) << "only the left eye";
    } else {
      EXPECT_GT(right[2], 150);
      EXPECT_LT(right[0], 60) << "the right eye is blue";
    }
    // "sim 12.345 s" at scale 2 in the top-left corner: light glyph pixels on the dark box
    const render::TextBox box = render::text_box(2, 2, 2, "sim 12.345 s");
    int light = 0;
    for (int y = box.y; y < box.y + box.height; ++y) {
      for (int x = box.x; x < box.x + box.width; ++x)
        light += image.at(x, y)[1] > 180;
    }
    EXPECT_GT(light, 100) << "the label is in the picture";
    EXPECT_LT(image.at(box.x + box.width + 10, 10)[1], 60) << "no label beyond its box";
  }
}

TEST(VideoRecorder, MissingProgramThrowsNamingItAndLeavesNoFile) {
  Recording r = recording("none.mp4");
  r.options.ffmpeg = "/nonexistent/ffmpeg";
  try {
    VideoRecorder video(r.options, 64, 48);
    FAIL() << "started a program that does not exist";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/ffmpeg"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(files_in(r.dir).empty());
}

TEST(VideoRecorder, FfmpegFailingIsReportedWithItsLogAndNoVideo) {
  SKIP_WITHOUT_FFMPEG();
  Recording r = recording("bad.mp4");
  r.options.preset = "no_such_preset";  // ffmpeg exits at start
  VideoRecorder video(r.options, 64, 48);
  const std::vector<uint8_t> frame = stereo_frame(64, 48, 0);
  for (int i = 0; i < 400 && video.dropped() == 0; ++i) {
    video.submit(frame.data(), frame_time_ns(60.0, i), 0);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  EXPECT_FALSE(video.finish());
  EXPECT_NE(video.error().find("exit status"), std::string::npos) << video.error();
  EXPECT_NE(video.error().find("no_such_preset"), std::string::npos) << "ffmpeg's own words";
  EXPECT_GT(video.dropped(), 0u) << "submits after the failure are dropped";
  EXPECT_FALSE(fs::exists(r.options.path));
  EXPECT_FALSE(fs::exists(r.options.path + ".partial"));
  EXPECT_TRUE(fs::exists(r.options.path + ".ffmpeg.log")) << "kept to say what went wrong";
  EXPECT_FALSE(video.finish()) << "the same answer again";
}

TEST(VideoRecorder, NoFramesIsAnErrorWithNoFileLeft) {
  SKIP_WITHOUT_FFMPEG();
  Recording r = recording("empty.mp4");
  VideoRecorder video(r.options, 64, 48);
  EXPECT_FALSE(video.finish());
  EXPECT_NE(video.error().find("no frames"), std::string::npos) << video.error();
  EXPECT_TRUE(files_in(r.dir).empty());
}

TEST(VideoRecorder, AFullQueueDropsFramesWithoutBlocking) {
  SKIP_WITHOUT_FFMPEG();
  Recording r = recording("burst.mp4");
  r.options.queue_frames = 1;
  r.options.preset = "veryfast";
  VideoRecorder video(r.options, 1280, 720);
  const std::vector<uint8_t> frame = stereo_frame(1280, 720, 0);
  const int burst = 30;
  const auto start = std::chrono::steady_clock::now();
  int accepted = 0;
  for (int i = 0; i < burst; ++i)
    accepted += video.submit(frame.data(), frame_time_ns(60.0, i), 0);
  const double burst_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(video.submitted(), uint64_t{burst});
  EXPECT_GT(video.dropped(), 0u);
  EXPECT_EQ(video.dropped(), uint64_t(burst - accepted));
  std::printf("burst of %d 1280x720 submits: %.2f ms, %d accepted\n", burst, burst_ms, accepted);
#if !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__)
  // a submit that waited for the encoder would cost at least one 1280x720 x264 frame (about
  // 10 ms) for each of the 29 later ones; the copies alone take about 1 ms each at most
  EXPECT_LT(burst_ms, 150.0);
#endif
  ASSERT_TRUE(video.finish()) << video.error();
  // each accepted frame is in the video, plus the last image once more at the last rendered
  // frame's period when frames were dropped at the end
  const uint64_t encoded = uint64_t(accepted) - video.skipped();
  EXPECT_GE(video.video_frames(), encoded);
  EXPECT_LE(video.video_frames(), encoded + 1);
  // the dropped ones, the last ones too, are held: the video lasts as long as the burst
  EXPECT_EQ(video.video_frames() + video.repeated(), uint64_t{burst});
  const Probe p = probe(r.options.path);
  EXPECT_EQ(p.frames, static_cast<int>(video.video_frames()));
  EXPECT_NEAR(p.duration_s, burst / 60.0, 1e-3);
}

TEST(VideoRecorder, NoAllocationPerFrame) {
  SKIP_WITHOUT_FFMPEG();
  Recording r = recording("alloc.mp4");
  r.options.scale_down = 2;
  VideoRecorder video(r.options, 96, 64);
  const std::vector<uint8_t> frame = stereo_frame(96, 64, 0);
  bool kept_up = true;
  auto submit_and_wait = [&](int i) {
    video.submit(frame.data(), frame_time_ns(60.0, 2 * i), i);  // every other period: holds too
    kept_up &= wait_for([&] { return video.video_frames() == static_cast<uint64_t>(i + 1); });
  };
  for (int i = 0; i < 3; ++i)
    submit_and_wait(i);  // warm up
  test::g_allocations = 0;
  test::g_count_allocations = true;
  for (int i = 3; i < 20; ++i)
    submit_and_wait(i);
  test::g_count_allocations = false;
  ASSERT_TRUE(kept_up) << video.video_frames() << " video frames";
  EXPECT_EQ(test::g_allocations.load(), 0);
  EXPECT_EQ(video.repeated(), 19u);
  ASSERT_TRUE(video.finish()) << video.error();
}

struct Child {
  pid_t pid = -1;
  int nice = 0;
  int policy = -1;  // SCHED_OTHER 0, SCHED_IDLE 5
};

// This process's child named ffmpeg, from /proc (pid -1 if there is none).
Child ffmpeg_child() {
  for (const auto& entry : fs::directory_iterator("/proc")) {
    const std::string name = entry.path().filename();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream in(entry.path() / "stat");
    std::string stat((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::size_t close = stat.rfind(')');
    if (close == std::string::npos || stat.find("(ffmpeg)") == std::string::npos) continue;
    std::istringstream fields(stat.substr(close + 2));  // from field 3, the state
    std::string field;
    std::vector<std::string> values;
    while (fields >> field)
      values.push_back(field);
    if (values.size() < 39 || std::stoi(values[1]) != getpid()) continue;  // field 4: ppid
    // field 19: nice, field 41: policy
    return {std::stoi(name), std::stoi(values[16]), std::stoi(values[38])};
  }
  return {};
}

TEST(VideoRecorder, FfmpegRunsAtLowerPriority) {
  SKIP_WITHOUT_FFMPEG();
  Recording r = recording("nice.mp4");
  VideoRecorder video(r.options, 64, 48);
  const Child ffmpeg = ffmpeg_child();
  ASSERT_GT(ffmpeg.pid, 0);
  EXPECT_EQ(ffmpeg.policy, SCHED_IDLE) << "below rendering and physics, whatever their nice";
  const std::vector<uint8_t> frame = stereo_frame(64, 48, 0);
  ASSERT_TRUE(video.submit(frame.data(), frame_time_ns(60.0, 0), 0));
  ASSERT_TRUE(video.finish()) << video.error();
}

TEST(VideoRecorder, FfmpegKilledMidRunIsAnErrorNotACrash) {
  SKIP_WITHOUT_FFMPEG();
  Recording r = recording("killed.mp4");
  r.options.queue_frames = 5;
  VideoRecorder video(r.options, 96, 64);
  const std::vector<uint8_t> frame = stereo_frame(96, 64, 0);
  for (int i = 0; i < 5; ++i)
    ASSERT_TRUE(video.submit(frame.data(), frame_time_ns(60.0, i), 0));
  ASSERT_TRUE(wait_for([&] { return video.video_frames() == 5; }));
  const pid_t pid = ffmpeg_child().pid;
  ASSERT_GT(pid, 0);
  kill(pid, SIGKILL);
  // the worker finds out at its next write (EPIPE, not SIGPIPE); submits after that are dropped
  int i = 5;
  EXPECT_TRUE(wait_for([&] {
    video.submit(frame.data(), frame_time_ns(60.0, i++), 0);
    return video.dropped() > 0;
  }));
  EXPECT_FALSE(video.finish());
  EXPECT_NE(video.error().find("killed by signal 9"), std::string::npos) << video.error();
  EXPECT_FALSE(fs::exists(r.options.path));
  EXPECT_FALSE(fs::exists(r.options.path + ".partial"));
}

// A stand-in for ffmpeg that reads its input and then never exits: finish() must not hang with it
// (the launcher would SIGKILL the node), and must say the video is lost.
TEST(VideoRecorder, AnFfmpegThatNeverFinishesIsKilledAfterTheTimeout) {
  Recording r = recording("hang.mp4");
  const std::string program = r.dir + "/hanging_ffmpeg";
  {
    std::ofstream script(program);
    script << "#!/bin/sh\ncat > /dev/null\nexec sleep 60\n";
  }
  fs::permissions(program, fs::perms::owner_all);
  r.options.ffmpeg = program;
  r.options.finish_timeout_s = 0.5;
  VideoRecorder video(r.options, 64, 48);
  const std::vector<uint8_t> frame = stereo_frame(64, 48, 0);
  ASSERT_TRUE(video.submit(frame.data(), frame_time_ns(60.0, 0), 0));
  const auto start = std::chrono::steady_clock::now();
  EXPECT_FALSE(video.finish());
  const double finish_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_GE(finish_s, 0.4);
  EXPECT_LT(finish_s, 2.0) << "bounded by finish_timeout_s";
  EXPECT_NE(video.error().find("not finished 0.5 s after"), std::string::npos) << video.error();
  EXPECT_FALSE(fs::exists(r.options.path));
  EXPECT_FALSE(fs::exists(r.options.path + ".partial"));
}

}  // namespace
}  // namespace vcockpit
