// Glove log reader and writer: the canonical format round-trips exactly, and every bad input is
// an error naming the file, the line and the column.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>

#include "hand/glove_log.hpp"
#include "hand/config/hand_yaml.hpp"
#include "tests/support/process.hpp"

namespace vcockpit::hand {
namespace {

hand::HandModel default_hand() {
  return load_hand_model(std::string(std::getenv("VCOCKPIT_SOURCE_DIR")) + "/config/hand.yaml");
}

class GloveLogTest : public ::testing::Test {
 protected:
  std::string dir_ = test::make_temp_dir("glove_log_test");
  hand::HandModel hand_ = default_hand();

  std::string write(const std::string& name, const std::string& text) {
    const std::string path = dir_ + "/" + name;
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }
  std::string error_of(const std::string& path) {
    try {
      read_glove_log(path, hand_);
    } catch (const GloveLogError& e) {
      return e.what();
    }
    return "(no error)";
  }
};

constexpr const char* kHeader = "t_s,x_m,y_m,z_m,qw,qx,qy,qz,index_mcp_deg\n";

TEST_F(GloveLogTest, CanonicalLogRoundTripsBitExactly) {
  std::vector<GloveSample> samples;
  for (int i = 0; i < 50; ++i) {
    GloveSample s;
    s.t_ns = 1'000'000LL * i + 333;  // not a round number of seconds
    s.p_MT_m = Eigen::Vector3d(0.1 + 1.0 / (i + 3), -0.2, 0.9 + 1e-9 * i);
    s.q_MT = Eigen::Quaterniond(Eigen::AngleAxisd(0.01 * i, Eigen::Vector3d(1, 2, 3).normalized()));
    s.joints_rad = hand_.rest_pose();
    s.joints_rad[static_cast<int>(hand::Joint::kIndexMcp)] = 0.5 + 1.0 / (i + 7);
    samples.push_back(s);
  }
  const std::string path = dir_ + "/roundtrip.csv";
  write_glove_log(path, samples, /*left_hand=*/true, {"source: unit test"});
  EXPECT_FALSE(std::filesystem::exists(path + ".partial"));
  const GloveLog log = read_glove_log(path, hand_);
  EXPECT_TRUE(log.left_hand);
  EXPECT_TRUE(log.missing_joints.empty());
  ASSERT_EQ(log.samples.size(), samples.size());
  for (std::size_t i = 0; i < samples.size(); ++i) {
    EXPECT_EQ(log.samples[i].t_ns, samples[i].t_ns);
    EXPECT_EQ(log.samples[i].p_MT_m, samples[i].p_MT_m);
    EXPECT_EQ(log.samples[i].q_MT.coeffs(), samples[i].q_MT.coeffs());
    EXPECT_EQ(log.samples[i].joints_rad, samples[i].joints_rad);
  }
  // writing what was read gives the same bytes
  const std::string again = dir_ + "/roundtrip2.csv";
  write_glove_log(again, log.samples, true, {"source: unit test"});
  std::ifstream a(path), b(again);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(a), {}),
            std::string(std::istreambuf_iterator<char>(b), {}));
}

TEST_F(GloveLogTest, EulerDegreesAndMissingJointsTakeTheRestPose) {
  const auto path = write("euler.csv",
                          "# hand: right\n# calibration: none\n"
                          "t_s,x_m,y_m,z_m,psi_deg,theta_deg,gamma_deg,index_mcp_deg\n"
                          "0.0,0,0,0,90,0,0,30\n0.01,0,0,0,0,0,0,30\n");
  const GloveLog log = read_glove_log(path, hand_);
  ASSERT_EQ(log.samples.size(), 2u);
  EXPECT_EQ(log.missing_joints.size(), static_cast<std::size_t>(hand::kJointCount - 1));
  EXPECT_NEAR(log.samples[0].joints_rad[static_cast<int>(hand::Joint::kIndexMcp)],
              30.0 * M_PI / 180.0, 1e-12);
  EXPECT_EQ(log.samples[0].joints_rad[static_cast<int>(hand::Joint::kMiddleMcp)],
            hand_.rest_pose()[static_cast<int>(hand::Joint::kMiddleMcp)]);
  // psi is the first Euler angle of the configured convention; 90 deg about its axis
  const Eigen::Matrix3d R = log.samples[0].q_MT.toRotationMatrix();
  EXPECT_NEAR(std::abs(R.determinant()), 1.0, 1e-12);
  EXPECT_FALSE(R.isApprox(Eigen::Matrix3d::Identity(), 1e-6));
  EXPECT_EQ(log.samples[1].t_ns, 10'000'000);
}

TEST_F(GloveLogTest, ClampedValuesAndMissingColumnsAreCountedAndWarnedAbout) {
  // two joint columns of 22; three values beyond the limits in two rows
  const auto path = write("counts.csv",
                          "t_s,x_m,y_m,z_m,qw,qx,qy,qz,index_mcp_deg,index_pip_deg\n"
                          "0,0,0,0,1,0,0,0,500,-300\n0.01,0,0,0,1,0,0,0,10,10\n"
                          "0.02,0,0,0,1,0,0,0,-400,10\n");
  const GloveLog log = read_glove_log(path, hand_);
  EXPECT_EQ(log.counts.clamped, 3u);
  EXPECT_EQ(log.counts.missing_columns, static_cast<uint64_t>(hand::kJointCount - 2));
  EXPECT_EQ(log.counts.missing_columns, log.missing_joints.size());
  const auto warnings = glove_log_warnings(log);
  ASSERT_EQ(warnings.size(), 2u);
  EXPECT_NE(warnings[0].find("no column for 20 joint(s), using the rest pose: thumb_rotation"),
            std::string::npos)
      << warnings[0];
  EXPECT_NE(warnings[1].find("3 joint value(s) beyond the limits were clamped; first: "),
            std::string::npos)
      << warnings[1];
  EXPECT_NE(warnings[1].find("counts.csv:2: column 'index_mcp_deg'"), std::string::npos)
      << warnings[1];
}

TEST_F(GloveLogTest, BeyondLimitsIsClampedAndCounted) {
  const auto path = write("limits.csv", std::string(kHeader) +
                                            "0,0,0,0,1,0,0,0,500\n0.01,0,0,0,1,0,0,0,10\n");
  const GloveLog log = read_glove_log(path, hand_);
  EXPECT_EQ(log.counts.clamped, 1u);
  EXPECT_NE(log.first_clamp.find("limits.csv:2: column 'index_mcp_deg'"), std::string::npos)
      << log.first_clamp;
  EXPECT_EQ(log.samples[0].joints_rad[static_cast<int>(hand::Joint::kIndexMcp)],
            hand_.joints[static_cast<int>(hand::Joint::kIndexMcp)].max_rad);
}

struct BadCase {
  const char* name;
  std::string text;
  std::string expected;  // substring of the error
};

TEST_F(GloveLogTest, EveryBadInputNamesFileLineAndColumn) {
  const std::vector<BadCase> cases = {
      {"non_numeric", std::string(kHeader) + "0,0,0,0,1,0,0,0,1\n0.01,0,abc,0,1,0,0,0,1\n",
       "non_numeric.csv:3: column 'y_m': not a number: 'abc'"},
      {"nan", std::string(kHeader) + "0,0,0,nan,1,0,0,0,1\n",
       "nan.csv:2: column 'z_m': not a finite number"},
      {"inf", std::string(kHeader) + "0,0,0,0,1,0,0,0,inf\n",
       "inf.csv:2: column 'index_mcp_deg': not a finite number"},
      {"backwards", std::string(kHeader) + "0.02,0,0,0,1,0,0,0,1\n0.01,0,0,0,1,0,0,0,1\n",
       "backwards.csv:3: column 't_s': time does not increase"},
      {"repeated", std::string(kHeader) + "0.02,0,0,0,1,0,0,0,1\n0.02,0,0,0,1,0,0,0,1\n",
       "repeated.csv:3: column 't_s': time does not increase"},
      {"truncated", std::string(kHeader) + "0,0,0,0,1,0,0,0,1\n0.01,0,0,0,1,0",
       "truncated.csv:3: truncated last line: 6 of 9 fields"},
      {"short_row", std::string(kHeader) + "0,0,0,0,1,0,0\n0.01,0,0,0,1,0,0,0,1\n",
       "short_row.csv:2: expected 9 fields, found 7"},
      {"unknown_column", "t_s,x_m,y_m,z_m,qw,qx,qy,qz,index_mpc_deg\n0,0,0,0,1,0,0,0,1\n",
       "unknown_column.csv:1: column 'index_mpc_deg': unknown column"},
      {"no_unit", "t_s,x_m,y_m,z_m,qw,qx,qy,qz,index_mcp\n0,0,0,0,1,0,0,0,1\n",
       "no_unit.csv:1: column 'index_mcp': unknown column"},
      {"twice", "t_s,x_m,y_m,z_m,qw,qx,qy,qz,x_m\n", "twice.csv:1: column 'x_m': column appears twice"},
      {"no_time", "x_m,y_m,z_m,qw,qx,qy,qz\n0,0,0,1,0,0,0\n", "no_time.csv:1: column 't_s': required"},
      {"mixed_orientation", "t_s,x_m,y_m,z_m,qw,qx,qy,psi_rad\n0,0,0,0,1,0,0,0\n",
       "mixed_orientation.csv:1: wrist orientation needs"},
      {"bad_quaternion", std::string(kHeader) + "0,0,0,0,2,0,0,0,1\n",
       "bad_quaternion.csv:2: column 'qw': wrist quaternion is not unit length"},
      {"bad_side", "# hand: middle\n" + std::string(kHeader) + "0,0,0,0,1,0,0,0,1\n",
       "bad_side.csv:1: hand must be 'left' or 'right'"},
      {"empty", "", "empty.csv: empty log"},
      {"comments_only", "# hand: right\n\n", "comments_only.csv: empty log"},
      {"header_only", "# hand: right\n" + std::string(kHeader), "header_only.csv:2: header only"},
      {"partly_nan", std::string(kHeader) + "0,0,0,0,1,0,0,0,1\n0.01,nan,nan,nan,nan,nan,nan,nan,1\n",
       "partly_nan.csv:3: column 'x_m': not a finite number"},
      {"dropouts_only", std::string(kHeader) + "0,nan,nan,nan,nan,nan,nan,nan,nan\n",
       "dropouts_only.csv: every one of the 1 samples is a dropout"},
      {"dropout_backwards",
       std::string(kHeader) + "0.02,0,0,0,1,0,0,0,1\n0.01,nan,nan,nan,nan,nan,nan,nan,nan\n",
       "dropout_backwards.csv:3: column 't_s': time does not increase"},
      {"after_dropout_backwards",
       std::string(kHeader) + "0.01,nan,nan,nan,nan,nan,nan,nan,nan\n0.01,0,0,0,1,0,0,0,1\n",
       "after_dropout_backwards.csv:3: column 't_s': time does not increase"},
  };
  for (const auto& c : cases) {
    const auto path = write(std::string(c.name) + ".csv", c.text);
    const std::string msg = error_of(path);
    EXPECT_NE(msg.find(c.expected), std::string::npos)
        << c.name << ": expected '" << c.expected << "' in: " << msg;
  }
  EXPECT_NE(error_of(dir_ + "/does_not_exist.csv").find("cannot open"), std::string::npos);
}

// Whose hand a log is, from its comment lines alone (the offline runner and the rig launcher
// give each log to its hand this way): as read_glove_log says, and a bad side names file:line.
TEST_F(GloveLogTest, ItsHandIsReadFromTheCommentLinesAlone) {
  const std::string row = "0,0,0,0.5,1,0,0,0,10\n";
  const std::string left = write("left.csv", "# vcockpit glove log\n# hand: left\n" + std::string(kHeader) + row);
  const std::string right = write("right.csv", "# hand: right\n" + std::string(kHeader) + row);
  const std::string unsaid = write("unsaid.csv", std::string(kHeader) + row + "# hand: left\n");
  EXPECT_TRUE(glove_log_left_hand(left));
  EXPECT_EQ(glove_log_left_hand(left), read_glove_log(left, hand_).left_hand);
  EXPECT_FALSE(glove_log_left_hand(right));
  EXPECT_FALSE(glove_log_left_hand(unsaid)) << "only the comment lines before the header count";
  const std::string bad = write("bad.csv", "# a log\n# hand: middle\n" + std::string(kHeader) + row);
  try {
    glove_log_left_hand(bad);
    FAIL() << "a side neither left nor right was taken";
  } catch (const GloveLogError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.csv:2:"), std::string::npos) << e.what();
  }
  EXPECT_THROW(glove_log_left_hand(dir_ + "/no_such.csv"), GloveLogError);
}

TEST_F(GloveLogTest, DropoutRowsAreSkippedAndCounted) {
  const auto path = write("dropouts.csv", std::string(kHeader) +
                                              "0,0,0,0,1,0,0,0,1\n"
                                              "0.01,nan,NaN,nan,nan,nan,nan,nan,nan\n"
                                              "0.02,0,0,0,1,0,0,0,2\n"
                                              "0.03,nan,nan,nan,nan,nan,nan,nan,nan\n");
  const GloveLog log = read_glove_log(path, hand_);
  ASSERT_EQ(log.samples.size(), 2u);
  EXPECT_EQ(log.samples[1].t_ns, 20'000'000);
  EXPECT_EQ(log.dropped_samples, 2);
  EXPECT_NE(log.first_dropout.find("dropouts.csv:3: a dropout"), std::string::npos)
      << log.first_dropout;
}

TEST_F(GloveLogTest, WrittenDropoutsReadBackAsDropouts) {
  const std::string path = dir_ + "/written_dropouts.csv";
  GloveLogWriter writer(path, false, {});
  GloveSample s;
  s.joints_rad = hand_.rest_pose();
  writer.append(s);
  writer.append_dropout(1'000'000);
  s.t_ns = 2'000'000;
  writer.append(s);
  writer.commit();
  const GloveLog log = read_glove_log(path, hand_);
  EXPECT_EQ(log.samples.size(), 2u);
  EXPECT_EQ(log.dropped_samples, 1);
}

TEST_F(GloveLogTest, UncommittedWriterLeavesNoLogAndNoPartialFile) {
  const std::string path = dir_ + "/interrupted.csv";
  {
    GloveLogWriter writer(path, false, {});
    GloveSample s;
    writer.append(s);
    EXPECT_TRUE(std::filesystem::exists(path + ".partial"));
  }  // destroyed without commit, as when recording fails
  EXPECT_FALSE(std::filesystem::exists(path));
  EXPECT_FALSE(std::filesystem::exists(path + ".partial"));
}

}  // namespace
}  // namespace vcockpit::hand
