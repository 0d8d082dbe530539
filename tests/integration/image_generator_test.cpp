// image_generator as a real process over loopback DDS: a test publisher sends coloured boxes at
// known poses; the rendered left and right PNGs show each box's colour where the camera model
// projects its centre, the boxes shift between the eyes the way stereo geometry requires (closer
// box -> larger disparity), frame_info arrives for every frame with consistent stamps, and
// missing topics or a bad HMD config are clear errors with their own exit codes.

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <thread>

#include "image_generator/node/hmd_yaml.hpp"
#include "image_generator/render/camera.hpp"
#include "tests/support/monitor_log.hpp"
#include "tests/support/png_read.hpp"
#include "tests/support/process.hpp"
#include "tests/support/process_test.hpp"
#include "tests/support/test_env.hpp"

namespace vcockpit::test {
namespace {


// Head at (0, 0, 1) looking along +x; 640x360 per eye keeps the test quick.
constexpr const char* kTestHmd = R"(ipd_m: 0.063
width_px: 640
height_px: 360
near_m: 0.05
far_m: 20.0
fov_deg:
  left_eye:  {left: -52, right: 45, up: 42, down: -48}
  right_eye: {left: -45, right: 52, up: 42, down: -48}
head: {position: [0.0, 0.0, 1.0], rpy_deg: [0, 0, 0]}
refresh_hz: 40
)";

struct Box {
  std::array<double, 3> rgb;
  Eigen::Vector3d p_G;
  double size_m;
  std::string arg() const {
    char buf[128];
    std::snprintf(buf, sizeof buf, "%g,%g,%g,%g,%g,%g,%g", rgb[0], rgb[1], rgb[2], p_G.x(),
                  p_G.y(), p_G.z(), size_m);
    return buf;
  }
};

// Mean column of the pixels whose dominant channel is `channel` (0 red, 1 green) by a margin.
double mean_column_of(const RgbaImage& image, int channel) {
  double sum = 0;
  int count = 0;
  for (int r = 0; r < image.height; ++r) {
    for (int c = 0; c < image.width; ++c) {
      const auto px = image.at(c, r);
      const int other = channel == 0 ? std::max(px[1], px[2]) : std::max(px[0], px[2]);
      if (px[channel] > 80 && px[channel] > other + 50) {
        sum += c;
        ++count;
      }
    }
  }
  return count > 0 ? sum / count : -1.0;
}

class ImageGeneratorTest : public ProcessTest {
 protected:
  void SetUp() override {
    ProcessTest::SetUp();
    std::ofstream(dir_ + "/hmd.yaml") << kTestHmd;
  }
  // The image generator on what the scene publisher shows: five frames, the fifth written per
  // eye as frames/frame_000004_{left,right}.png; its exit status.
  int render_five_frames() {
    ChildProcess ig = start("image_generator",
                            {"--hmd", dir_ + "/hmd.yaml", "--frames", "5", "--fps", "0", "--out",
                             dir_ + "/frames", "--snapshot-every", "4", "--snapshot-layout", "both"},
                            "ig.log");
    return ig.wait(60 * kSecond);
  }
};

// A MESH object over DDS (the ramp of tests/data/models at half its size, as the physics node
// announces a model part): the image generator reads the file named in its object_info and draws
// the part where its pose puts it, its material's colour times the object's.
TEST_F(ImageGeneratorTest, AModelPartShowsAtItsProjectedPixel) {
  const Eigen::Vector3d p_G(0.8, 0.0, 0.97);  // on its back face (x = 0.8, z 0.9 .. 1.046)
  ChildProcess scene = start("test_scene_pub",
                             {"--mesh", std::string(std::getenv("VCOCKPIT_SOURCE_DIR")) +
                                            "/tests/data/models/ramp.gltf,ramp,0.5,0,0,1,1.0,0,0.9"},
                             "scene.log");
  ASSERT_EQ(render_five_frames(), 0) << text("ig.log");
  EXPECT_EQ(scene.stop(), 0);
  EXPECT_NE(text("ig.log").find("object 'mesh0': model "), std::string::npos) << text("ig.log");
  const HmdSetup hmd = load_hmd_config(dir_ + "/hmd.yaml");
  for (const auto& [eye, name] : {std::pair{render::Eye::kLeft, "left"}, {render::Eye::kRight, "right"}}) {
    RgbaImage image;
    ASSERT_TRUE(read_png(dir_ + "/frames/frame_000004_" + name + ".png", image)) << text("ig.log");
    Eigen::Vector2d pixel;
    ASSERT_TRUE(render::project_to_pixel(hmd.hmd, eye, hmd.X_GHead, p_G, pixel));
    const auto px = image.at(static_cast<int>(pixel.x()), static_cast<int>(pixel.y()));
    EXPECT_GT(px[2], std::max(px[0], px[1]) + 50)
        << "the blue part not at its projected pixel in the " << name << " eye: rgba " << px[0]
        << " " << px[1] << " " << px[2];
  }
}

TEST_F(ImageGeneratorTest, BoxesShowAtTheirProjectedPixelsWithStereoDisparity) {
  const Box far_red{{1, 0, 0}, {1.0, -0.15, 1.0}, 0.10};
  const Box near_green{{0, 1, 0}, {0.5, 0.12, 1.0}, 0.06};
  ChildProcess scene = start("test_scene_pub", {"--box", far_red.arg(), "--box", near_green.arg()},
                             "scene.log");
  ASSERT_EQ(render_five_frames(), 0) << text("ig.log");
  EXPECT_EQ(scene.stop(), 0);

  RgbaImage left, right;
  ASSERT_TRUE(read_png(dir_ + "/frames/frame_000004_left.png", left)) << text("ig.log");
  ASSERT_TRUE(read_png(dir_ + "/frames/frame_000004_right.png", right));
  ASSERT_EQ(left.width, 640);
  ASSERT_EQ(left.height, 360);

  const HmdSetup hmd = load_hmd_config(dir_ + "/hmd.yaml");
  for (const auto* box : {&far_red, &near_green}) {
    const int channel = box->rgb[0] > 0.5 ? 0 : 1;
    for (auto [eye, image] : {std::pair{render::Eye::kLeft, &left}, {render::Eye::kRight, &right}}) {
      Eigen::Vector2d pixel;
      ASSERT_TRUE(render::project_to_pixel(hmd.hmd, eye, hmd.X_GHead, box->p_G, pixel));
      const auto px = image->at(static_cast<int>(pixel.x()), static_cast<int>(pixel.y()));
      const int other = channel == 0 ? std::max(px[1], px[2]) : std::max(px[0], px[2]);
      EXPECT_GT(px[channel], other + 50)
          << (channel == 0 ? "red" : "green") << " box not at its projected pixel ("
          << pixel.transpose() << ") in the " << (eye == render::Eye::kLeft ? "left" : "right")
          << " eye: rgba " << px[0] << " " << px[1] << " " << px[2];
    }
  }
  // Stereo: the eyes' frusta are asymmetric, so even a point at infinity lands at different
  // columns; disparity is the shift beyond that. A nearer point appears further right in the left
  // eye (further left in the right eye), and nearer means larger disparity.
  auto column = [&](render::Eye eye, const Eigen::Vector3d& p_G) {
    Eigen::Vector2d pixel;
    EXPECT_TRUE(render::project_to_pixel(hmd.hmd, eye, hmd.X_GHead, p_G, pixel));
    return pixel.x();
  };
  const Eigen::Vector3d far_ahead = hmd.X_GHead * Eigen::Vector3d(1000.0, 0, 0);
  const double infinity_offset =
      column(render::Eye::kLeft, far_ahead) - column(render::Eye::kRight, far_ahead);
  const double red_disparity = mean_column_of(left, 0) - mean_column_of(right, 0) - infinity_offset;
  const double green_disparity =
      mean_column_of(left, 1) - mean_column_of(right, 1) - infinity_offset;
  std::printf("disparity beyond infinity's %.1f px: red box at 1.0 m %.1f px, green at 0.5 m "
              "%.1f px\n",
              infinity_offset, red_disparity, green_disparity);
  EXPECT_GT(red_disparity, 0.0);
  EXPECT_GT(green_disparity, red_disparity * 1.5);
  // and the rendered shift is the one the camera model predicts for each box
  for (auto [box, measured] : {std::pair{&far_red, red_disparity}, {&near_green, green_disparity}}) {
    const double predicted = column(render::Eye::kLeft, box->p_G) -
                             column(render::Eye::kRight, box->p_G) - infinity_offset;
    EXPECT_NEAR(measured, predicted, 3.0);
  }
}

// frame_info is best effort (the stream profile): a reader sees the frames from the moment it
// has matched the image generator's writer. Discovery usually takes 10-15 ms but now and then
// over a second (a lost first exchange waits for a resend), so the run is long enough to leave
// most frames after the match, and nearly every frame from the first one seen must arrive, in
// order.
TEST_F(ImageGeneratorTest, FrameInfoArrivesForEveryFrameWithConsistentStamps) {
  constexpr int kFrames = 180;  // 3 s at 60 fps
  constexpr int64_t kHandStamp = 123456789;
  ChildProcess scene = start("test_scene_pub",
                             {"--box", "1,0,0,1,0,1,0.1", "--hand-stamp", std::to_string(kHandStamp)},
                             "scene.log");
  ChildProcess monitor = start("test_cockpit_monitor", {"--out", dir_ + "/monitor.txt"}, "monitor.log");
  std::this_thread::sleep_for(std::chrono::milliseconds(500));  // the monitor matches first
  ChildProcess ig = start("image_generator", {"--hmd", dir_ + "/hmd.yaml", "--frames",
                                              std::to_string(kFrames), "--fps", "60"},
                          "ig.log");
  ASSERT_EQ(ig.wait(60 * kSecond), 0) << text("ig.log");
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  EXPECT_EQ(monitor.stop(), 0);
  EXPECT_EQ(scene.stop(), 0);

  const MonitorLog seen = MonitorLog::read(dir_ + "/monitor.txt");
  ASSERT_GE(seen.frames.size(), static_cast<std::size_t>(kFrames / 2))
      << "most frames are rendered after the monitor matched\n" << text("ig.log");
  const uint64_t first = seen.frames.front().seq;
  // Best effort over loopback loses a sample now and then (a full socket buffer while the reader
  // is descheduled on a loaded 2-core machine): allow one in a hundred, never out of order.
  const std::size_t expected = static_cast<std::size_t>(kFrames) - first;
  EXPECT_LE(seen.frames.size(), expected);
  EXPECT_GE(seen.frames.size(), expected - expected / 100)
      << "nearly every frame from the first seen";
  EXPECT_LT(seen.frames.back().seq, static_cast<uint64_t>(kFrames));
  for (std::size_t i = 0; i < seen.frames.size(); ++i) {
    const SeenFrame& f = seen.frames[i];
    if (i > 0) {
      EXPECT_GT(f.seq, seen.frames[i - 1].seq) << "in order";
    }
    EXPECT_EQ(f.width, 640);
    EXPECT_EQ(f.height, 360);
    EXPECT_LE(f.start_ns, f.end_ns);
    EXPECT_LE(f.end_ns, f.received_ns) << "rendered before it was reported";
    if (i > 0) {
      EXPECT_GT(f.start_ns, seen.frames[i - 1].end_ns - 1);
    }
  }
  EXPECT_EQ(seen.frames.back().source_stamp_ns, kHandStamp) << "the hand data drawn";
}

// Pacing: frames at the HMD's refresh_hz by default, none late when the renderer keeps up; at a
// rate it cannot keep, late frames and missed display slots are counted and the frames are not
// bunched to catch up (the rate stays what the renderer can do). The static boxes are drawn
// into the background once.
TEST_F(ImageGeneratorTest, FramesArePacedToTheDisplayAndLateOnesAreCounted) {
  ChildProcess scene = start("test_scene_pub", {"--box", "1,0,0,1,0,1,0.1", "--box", "0,1,0,1.5,0.3,1,0.2"},
                             "scene.log");
  auto run = [&](std::vector<std::string> args, const std::string& name) {
    args.insert(args.end(), {"--hmd", dir_ + "/hmd.yaml", "--frames", "60", "--stats-out",
                             dir_ + "/" + name + ".json"});
    ChildProcess ig = start("image_generator", args, name + ".log");
    EXPECT_EQ(ig.wait(60 * kSecond), 0) << text(name + ".log");
    return nlohmann::json::parse(text(name + ".json"), nullptr, false);
  };
  const auto paced = run({}, "paced");
  ASSERT_TRUE(paced.is_object()) << text("paced.log");
  EXPECT_EQ(paced["paced_fps"], 40.0) << "hmd.yaml's refresh_hz";
  // 60 frames over 59 slots and one render: just above 40
  EXPECT_LE(paced["fps"].get<double>(), 41.0);
  if (!sanitized()) {
    EXPECT_GT(paced["fps"].get<double>(), 20.0);
    // a 0.5 ms frame in a 25 ms slot is late only when the process was not scheduled in time:
    // once here beside the scenario tests on two cores; a pacing that misses its slots misses
    // most of the 60 (so: fewer than half)
    EXPECT_LT(paced["late_frames"].get<int>(), 30) << text("paced.log");
  }
  EXPECT_EQ(paced["background_redraws"], 1) << "the boxes do not move";
  const auto too_fast = run({"--fps", "5000"}, "too_fast");
  ASSERT_TRUE(too_fast.is_object()) << text("too_fast.log");
  EXPECT_GT(too_fast["late_frames"].get<int>(), 30) << "a 0.2 ms slot is missed by nearly all";
  EXPECT_GE(too_fast["missed_slots"].get<int>(), too_fast["late_frames"].get<int>());
  const auto unpaced = run({"--fps", "0"}, "unpaced");
  ASSERT_TRUE(unpaced.is_object());
  EXPECT_EQ(unpaced["late_frames"], 0) << "no slots, none late";
  // two rates measured one after the other: under the sanitizers, beside other tests, the
  // unpaced run was once the slower one (85 against 122 fps under TSan)
  if (!sanitized()) {
    EXPECT_LE(too_fast["fps"].get<double>(), 1.2 * unpaced["fps"].get<double>())
        << "late frames are not bunched to catch up";
  }
  EXPECT_EQ(scene.stop(), 0);
}

TEST_F(ImageGeneratorTest, NoSceneAndBadHmdConfigAreClearErrors) {
  ChildProcess ig = start("image_generator",
                          {"--hmd", dir_ + "/hmd.yaml", "--wait-timeout", "1"}, "ig.log");
  EXPECT_EQ(ig.wait(20 * kSecond), 3);
  EXPECT_NE(text("ig.log").find("cockpit/object_info"), std::string::npos) << text("ig.log");

  std::ofstream(dir_ + "/bad_hmd.yaml") << "ipd_m: 0.063\nwidth_px: -5\n";
  ChildProcess bad = start("image_generator", {"--hmd", dir_ + "/bad_hmd.yaml"}, "bad.log");
  EXPECT_EQ(bad.wait(20 * kSecond), 1);
  EXPECT_NE(text("bad.log").find("bad_hmd.yaml:"), std::string::npos) << text("bad.log");
}

}  // namespace
}  // namespace vcockpit::test
