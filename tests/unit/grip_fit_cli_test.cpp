// grip_fit, the command: exit 0 and a scene that loads, its placement replayed and held; exit 1
// and the best placement's figures when none fits, or a line per candidate when none holds (no
// file); exit 2 and a clear error for bad flags and files (the loaders' file:line), never leaving
// a file.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "hand/glove_log.hpp"
#include "physics_node/config/scene_config.hpp"
#include "tests/support/process.hpp"
#include "tests/unit/grip_fit_samples.hpp"

namespace vcockpit::test {
namespace {

namespace fs = std::filesystem;

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

class GripFitCli : public ::testing::Test {
 protected:
  std::string dir_ = make_temp_dir("grip_fit_cli");
  std::string log_ = source_dir() + "/tests/data/real/leap_grab.csv";
  std::string out_ = dir_ + "/scene.yaml";

  // Exit code; output in dir_/<name>.out
  int run(const std::string& name, std::vector<std::string> args) {
    args.insert(args.begin(), GRIP_FIT_EXE);
    ChildProcess p(args, {}, dir_ + "/" + name + ".out");
    return p.wait(120'000'000'000);
  }
  std::string output(const std::string& name) { return read_text(dir_ + "/" + name + ".out"); }
};

TEST_F(GripFitCli, WritesASceneThatLoads) {
  ASSERT_EQ(run("ball", {"--log", log_, "--shape", "sphere", "--size", "0.025", "--out", out_,
                         "--mass", "0.05", "--name", "ball"}),
            0)
      << output("ball");
  const physics::Scene scene = load_scene(out_);
  const int ball = scene.find_object("ball");
  ASSERT_GE(ball, 0);
  EXPECT_DOUBLE_EQ(scene.objects[static_cast<std::size_t>(ball)].mass_kg, 0.05);
  EXPECT_GE(scene.find_object("pedestal"), 0);
  for (const char* expected : {"first closed stretch: t_s ", "  tried t_s ", ": HOLDS: GRASP ",
                               "moment: t_s 0.", "placement: sphere r 25.0 mm at p_G (", "thumb",
                               "deepest link:", "pedestal", "replayed: GRASP ", "wrote "}) {
    EXPECT_NE(output("ball").find(expected), std::string::npos) << expected << "\n"
                                                                << output("ball");
  }
  EXPECT_NE(read_text(out_).find("# Replayed on the log: GRASP "), std::string::npos);
  // --at forces the moment (the nearest sample); --no-verify takes its placement unreplayed
  ASSERT_EQ(run("at", {"--log", log_, "--shape", "sphere", "--size", "0.025", "--out", out_, "--at",
                       "0.6", "--no-verify"}),
            0)
      << output("at");
  // samples at 0.5983 and 0.6071 s: the first is nearer
  EXPECT_NE(output("at").find("moment: t_s 0.5983"), std::string::npos) << output("at");
  EXPECT_NE(output("at").find("forced by --at"), std::string::npos) << output("at");
  EXPECT_NE(output("at").find("replayed: no (--no-verify)"), std::string::npos) << output("at");
  EXPECT_NE(output("at").find(": taken unreplayed (--no-verify)"), std::string::npos)
      << output("at");
  EXPECT_NE(read_text(out_).find("# Not replayed (--no-verify)."), std::string::npos);
}

// A placement the replayed hand does not hold is not written: the closed fist at 0.6 s has swept
// through the ball's place before (it is never grasped), so --at 0.6 alone fails, naming why.
TEST_F(GripFitCli, NoPlacementThatHoldsExitsOneWithEachTrialAndWritesNothing) {
  EXPECT_EQ(run("held", {"--log", log_, "--shape", "sphere", "--size", "0.025", "--out", out_,
                         "--at", "0.6"}),
            1)
      << output("held");
  const std::string out = output("held");
  const auto tried = out.find("  tried t_s 0.5983 (closure ");
  ASSERT_NE(tried, std::string::npos) << out;
  EXPECT_NE(out.find("any, result 1 of 1 at (", tried), std::string::npos) << out;
  EXPECT_NE(out.find(": not grasped by ", tried), std::string::npos) << out;
  EXPECT_NE(output("held").find("no placement holds when replayed"), std::string::npos)
      << output("held");
  EXPECT_FALSE(fs::exists(out_));
  EXPECT_FALSE(fs::exists(out_ + ".partial"));
}

TEST_F(GripFitCli, NoPlacementExitsOneWithTheBestFiguresAndWritesNothing) {
  EXPECT_EQ(run("huge", {"--log", log_, "--shape", "sphere", "--size", "0.2", "--out", out_}), 1)
      << output("huge");
  EXPECT_NE(output("huge").find("no placement of the sphere r 200.0 mm"), std::string::npos)
      << output("huge");
  EXPECT_NE(output("huge").find("best miss:"), std::string::npos) << output("huge");
  EXPECT_NE(output("huge").find("deepest link:"), std::string::npos) << output("huge");
  EXPECT_FALSE(fs::exists(out_));
  EXPECT_FALSE(fs::exists(out_ + ".partial"));
}

TEST_F(GripFitCli, BadFlagsAndFilesExitTwoNamedAndWriteNothing) {
  const std::string broken = dir_ + "/broken.csv";
  std::ofstream(broken) << hand::canonical_header() << "\n0,1,2\n";
  // a hand file with a bad value on its line 3
  const std::string bad_hand = dir_ + "/bad_hand.yaml";
  {
    std::string text = read_text(source_dir() + "/config/hand.yaml");
    text = std::regex_replace(text, std::regex("\nside: right\n"), "\nside: middle\n");
    std::ofstream(bad_hand) << text;
  }
  struct Case {
    const char* name;
    std::vector<std::string> args;
    const char* expected;
  };
  const std::vector<std::string> ok = {"--log", log_, "--out", out_};
  const auto with = [&](std::vector<std::string> more) {
    std::vector<std::string> args = ok;
    args.insert(args.end(), more.begin(), more.end());
    return args;
  };
  const std::vector<Case> cases = {
      {"shape", with({"--shape", "cone", "--size", "0.01"}), "--shape"},
      {"count", with({"--shape", "cylinder", "--size", "0.01"}), "a cylinder takes 2 numbers"},
      {"negative", with({"--shape", "sphere", "--size", "-0.01"}), "--size"},
      {"nan_mass", with({"--shape", "sphere", "--size", "0.02", "--mass", "nan"}),
       "not a finite number"},
      {"at", with({"--shape", "sphere", "--size", "0.02", "--at", "9"}),
       "outside the log's t_s range"},
      {"name", with({"--shape", "sphere", "--size", "0.02", "--name", "a b"}), "--name"},
      {"out_dir",
       {"--log", log_, "--out", dir_ + "/missing/scene.yaml", "--shape", "sphere", "--size",
        "0.02"},
       "does not exist"},
      {"missing_log",
       {"--log", dir_ + "/missing.csv", "--out", out_, "--shape", "sphere", "--size", "0.02"},
       "missing.csv"},
      {"broken_log",
       {"--log", broken, "--out", out_, "--shape", "sphere", "--size", "0.02"},
       "broken.csv:2"},
      {"bad_hand", with({"--hand", bad_hand, "--shape", "sphere", "--size", "0.02"}),
       "bad_hand.yaml:"},
      {"no_shape", ok, "--shape"},
  };
  for (const auto& c : cases) {
    EXPECT_EQ(run(c.name, c.args), 2) << c.name << ": " << output(c.name);
    EXPECT_NE(output(c.name).find(c.expected), std::string::npos)
        << c.name << ": " << output(c.name);
    EXPECT_FALSE(fs::exists(out_)) << c.name;
    EXPECT_FALSE(fs::exists(out_ + ".partial")) << c.name;
  }
  EXPECT_EQ(run("help", {"--help"}), 0);
  for (const char* flag : {"--log", "--hand", "--shape", "--size", "--out", "--mass", "--at",
                           "--no-verify", "--cockpit"})
    EXPECT_NE(output("help").find(flag), std::string::npos) << flag;
}

}  // namespace
}  // namespace vcockpit::test
