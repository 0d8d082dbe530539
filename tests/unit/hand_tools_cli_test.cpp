// hand_import, hand_retarget and hand_calibrate, the commands: a Leap recording becomes a
// hand-joints log, then a glove log and a calibrated hand.yaml that load; hand_calibrate measures
// both hands of a recording into hand files that fit it better; a two-handed log without
// --out-left, or a bad input, is a clear error that writes nothing.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "hand/config/hand_yaml.hpp"
#include "hand/glove_log.hpp"
#include "hand/tracking/joints_log.hpp"
#include "tests/support/process.hpp"
#include "tests/support/test_files.hpp"

namespace vcockpit::test {
namespace {

namespace fs = std::filesystem;

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

class HandToolsCli : public ::testing::Test {
 protected:
  std::string dir_ = make_temp_dir("hand_tools_cli");

  int run(const std::string& name, std::vector<std::string> args) {
    ChildProcess p(args, {}, dir_ + "/" + name + ".out");
    return p.wait(120'000'000'000);
  }
  std::string output(const std::string& name) { return read_text(dir_ + "/" + name + ".out"); }
};

TEST_F(HandToolsCli, ALeapRecordingBecomesAGloveLogAndACalibratedHand) {
  const std::string joints = dir_ + "/grab_joints.csv";
  ASSERT_EQ(run("import", {HAND_IMPORT_EXE, "--from", "leapjs",
                           source_dir() + "/tests/data/real/leap/grab.json", "--out", joints}),
            0)
      << output("import");
  EXPECT_NE(output("import").find("374 rows (374 right, 0 left) from 374 frames"), std::string::npos)
      << output("import");
  EXPECT_EQ(hand::tracking::read_joints_log(joints).frames.size(), 374u);

  const std::string glove = dir_ + "/grab.csv", hand_yaml = dir_ + "/hand_grab.yaml";
  ASSERT_EQ(run("retarget", {HAND_RETARGET_EXE, joints, "--out", glove, "--calibrated-hand", hand_yaml,
                             "--hand-file", source_dir() + "/config/hand.yaml"}),
            0)
      << output("retarget");
  const hand::HandModel hand = load_hand_model(hand_yaml);
  const hand::GloveLog log = hand::read_glove_log(glove, hand);
  EXPECT_EQ(log.samples.size(), 374u);
  EXPECT_EQ(log.counts.clamped, 0u) << "the fit stays within the joints' ranges";
  EXPECT_NE(read_text(glove).find("# fingertip error of the fit p50"), std::string::npos);
}

// The calibrated hands fit their recording closer than the default hand, and retargeting on them
// gives what the calibrating retarget gives.
TEST_F(HandToolsCli, HandCalibrateWritesEachHandOfARecordingAsAHandFile) {
  const std::string claps = dir_ + "/claps.csv";
  ASSERT_EQ(run("import", {HAND_IMPORT_EXE, source_dir() + "/tests/data/real/leap/three-claps.json",
                           "--out", claps}),
            0)
      << output("import");
  const std::string right = dir_ + "/right.yaml", left = dir_ + "/left.yaml";
  ASSERT_EQ(run("calibrate", {HAND_CALIBRATE_EXE, claps, "--out", right, "--out-left", left}), 0)
      << output("calibrate");
  EXPECT_TRUE(load_hand_model(left).left);
  EXPECT_FALSE(load_hand_model(right).left);
  // "...: right hand, N steady frames, bones of 5 of 5 fingers measured; fingertip error p50 / p99
  // A / B mm on hand.yaml, C / D mm calibrated"
  for (const std::string side : {"right", "left"}) {
    const std::string out = output("calibrate");
    const std::size_t at = out.find(side + " hand, ");
    ASSERT_NE(at, std::string::npos) << out;
    double before_p50 = 0, before_p99 = 0, after_p50 = 0, after_p99 = 0;
    ASSERT_EQ(std::sscanf(out.c_str() + out.find("p50 / p99 ", at), "p50 / p99 %lf / %lf mm on hand.yaml, %lf / %lf",
                          &before_p50, &before_p99, &after_p50, &after_p99),
              4)
        << out;
    EXPECT_NE(out.find("bones of 5 of 5 fingers measured", at), std::string::npos) << out;
    EXPECT_LT(after_p50, 5.0) << side << ": " << out;
    EXPECT_LT(after_p50, before_p50 / 4) << side << ": " << out;
  }
  // the hand file it scales is never its output
  const std::string template_copy = dir_ + "/hand_copy.yaml";
  fs::copy_file(source_dir() + "/config/hand.yaml", template_copy);
  const std::string before = read_text(template_copy);
  EXPECT_NE(run("over", {HAND_CALIBRATE_EXE, claps, "--out", template_copy, "--out-left", left,
                         "--hand-file", template_copy}),
            0);
  EXPECT_NE(output("over").find("is the --hand-file"), std::string::npos) << output("over");
  EXPECT_EQ(read_text(template_copy), before);
  EXPECT_NE(run("no_left", {HAND_CALIBRATE_EXE, claps, "--out", dir_ + "/only.yaml"}), 0);
  EXPECT_NE(output("no_left").find("has a left hand: give --out-left"), std::string::npos) << output("no_left");
  EXPECT_FALSE(fs::exists(dir_ + "/only.yaml"));
}

TEST_F(HandToolsCli, RefusedRunsWriteNothing) {
  const std::string claps = dir_ + "/claps.csv";
  ASSERT_EQ(run("import", {HAND_IMPORT_EXE, source_dir() + "/tests/data/real/leap/three-claps.json",
                           "--out", claps}),
            0)
      << output("import");
  const std::string right = dir_ + "/right.csv";
  EXPECT_NE(run("no_left", {HAND_RETARGET_EXE, claps, "--out", right}), 0);
  EXPECT_NE(output("no_left").find("has a left hand: give --out-left"), std::string::npos) << output("no_left");
  EXPECT_FALSE(fs::exists(right)) << "nothing written when one output is missing";

  std::ofstream(dir_ + "/bad.json") << "{\"frames\": [";
  EXPECT_NE(run("bad", {HAND_IMPORT_EXE, dir_ + "/bad.json", "--out", dir_ + "/bad.csv"}), 0);
  EXPECT_NE(output("bad").find("bad.json: not JSON"), std::string::npos) << output("bad");
  EXPECT_FALSE(fs::exists(dir_ + "/bad.csv"));
  EXPECT_NE(run("format", {HAND_IMPORT_EXE, "--from", "kinect", dir_ + "/bad.json", "--out", dir_ + "/x.csv"}), 0);
  EXPECT_NE(output("format").find("kinect"), std::string::npos) << output("format");
}

}  // namespace
}  // namespace vcockpit::test
