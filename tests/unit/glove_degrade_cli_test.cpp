// glove_degrade, the command: a degraded log the reader accepts (dropouts skipped and counted,
// values past range clamped and counted), the same bytes for the same command, and clear errors
// that leave no output for bad flags and files.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "hand/glove_log.hpp"
#include "tests/support/process.hpp"
#include "tests/unit/degrade_samples.hpp"

namespace vcockpit::test {
namespace {

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

class GloveDegradeCli : public ::testing::Test {
 protected:
  std::string dir_ = make_temp_dir("glove_degrade_cli");
  hand::HandModel hand_ = default_hand();
  std::string clean_ = dir_ + "/clean.csv";

  void SetUp() override {
    // every channel from below its range to past it: the calibration error takes some past
    hand::write_glove_log(clean_, sweep_log(hand_), false, {"source: the test's sweep"});
  }
  // Exit code; output in dir_/<name>.out
  int run(const std::string& name, std::vector<std::string> args) {
    args.insert(args.begin(), GLOVE_DEGRADE_EXE);
    ChildProcess p(args, {}, dir_ + "/" + name + ".out");
    return p.wait(60'000'000'000);
  }
  std::string output(const std::string& name) { return read_text(dir_ + "/" + name + ".out"); }
};

TEST_F(GloveDegradeCli, WritesALogTheReaderAcceptsAndCounts) {
  const std::string out = dir_ + "/typical.csv";
  ASSERT_EQ(run("typical", {"--in", clean_, "--out", out, "--preset", "typical", "--preset",
                            "overrange", "--seed", "4"}),
            0)
      << output("typical");
  const hand::GloveLog log = hand::read_glove_log(out, hand_);
  // 60 Hz over 4 s: 241 rows, 1 % of the 240 after the first are dropouts
  EXPECT_EQ(log.samples.size() + static_cast<std::size_t>(log.dropped_samples), 241u);
  EXPECT_EQ(log.dropped_samples, 2);
  EXPECT_GT(log.counts.clamped, 0);
  EXPECT_NE(output("typical").find("2 dropouts"), std::string::npos) << output("typical");
  EXPECT_NE(output("typical").find(std::to_string(log.counts.clamped) + " joint values past range"),
            std::string::npos)
      << output("typical") << " vs the reader's " << log.counts.clamped;
  bool described = false, source_kept = false;
  for (const auto& c : log.comments) {
    described = described || c.find("degraded from clean.csv: resampled to 60 Hz") == 0;
    source_kept = source_kept || c == "source: the test's sweep";
  }
  EXPECT_TRUE(described);
  EXPECT_TRUE(source_kept);
}

TEST_F(GloveDegradeCli, SameCommandSameBytes) {
  std::string text[2];
  for (int i = 0; i < 2; ++i) {
    const std::string out = dir_ + "/harsh" + std::to_string(i) + ".csv";
    ASSERT_EQ(run("harsh" + std::to_string(i), {"--in", clean_, "--out", out, "--preset", "harsh",
                                                "--seed", "9"}),
              0);
    text[i] = read_text(out);
  }
  EXPECT_GT(text[0].size(), 1000u);
  EXPECT_EQ(text[0], text[1]);
}

TEST_F(GloveDegradeCli, BadFlagsAndFilesAreNamedAndLeaveNoOutput) {
  const std::string out = dir_ + "/bad.csv";
  struct Case {
    const char* name;
    std::vector<std::string> args;
    const char* expected;
  };
  const std::vector<Case> cases = {
      {"preset", {"--in", clean_, "--out", out, "--preset", "40hz"}, "unknown preset '40hz'"},
      {"missing", {"--in", dir_ + "/missing.csv", "--out", out}, "missing.csv"},
      {"rate", {"--in", clean_, "--out", out, "--rate-hz", "0"}, "--rate-hz"},
      {"nan", {"--in", clean_, "--out", out, "--jitter-mm", "nan"}, "not a finite number"},
      {"same", {"--in", clean_, "--out", clean_}, "--out must not be the --in log"},
      {"gaps", {"--in", clean_, "--out", out, "--gaps", "9", "--gap-min", "0.6"},
       "cannot place 9 gaps"},
      {"no_out", {"--in", clean_}, "give --in LOG and --out LOG"},
  };
  for (const auto& c : cases) {
    EXPECT_NE(run(c.name, c.args), 0) << c.name;
    EXPECT_NE(output(c.name).find(c.expected), std::string::npos) << c.name << ": " << output(c.name);
    EXPECT_FALSE(std::filesystem::exists(out)) << c.name;
    EXPECT_FALSE(std::filesystem::exists(out + ".partial")) << c.name;
  }
  // a log the reader rejects is named with its line
  const std::string broken = dir_ + "/broken.csv";
  std::ofstream(broken) << hand::canonical_header() << "\n0,1,2\n";
  EXPECT_NE(run("broken", {"--in", broken, "--out", out}), 0);
  EXPECT_NE(output("broken").find("broken.csv:2"), std::string::npos) << output("broken");
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST_F(GloveDegradeCli, ListsItsPresets) {
  ASSERT_EQ(run("list", {"--list-presets"}), 0);
  for (const char* name : {"30hz", "60hz", "100hz", "120hz", "jitter", "glove_noise", "overrange",
                           "dropouts", "gaps", "grip250ms", "grip500ms", "typical", "harsh"}) {
    EXPECT_NE(output("list").find(name), std::string::npos) << name;
  }
}

}  // namespace
}  // namespace vcockpit::test
