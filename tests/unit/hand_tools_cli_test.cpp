// hand_import and hand_retarget, the commands: a Leap recording becomes a hand-joints log, then a
// glove log and a calibrated hand.yaml that load; a two-handed log without --out-left, or a bad
// input, is a clear error that writes nothing.

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
