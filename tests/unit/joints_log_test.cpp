// Hand-joints log reader and writer: frames round-trip exactly, lost joints stay lost, and every
// bad input is an error naming the file, the line and the column.

#include <gtest/gtest.h>

#include <fstream>
#include <functional>

#include "hand/tracking/joints_log.hpp"
#include "tests/support/process.hpp"

namespace vcockpit::hand::tracking {
namespace {

class JointsLogTest : public ::testing::Test {
 protected:
  std::string dir_ = test::make_temp_dir("joints_log_test");

  std::string write(const std::string& name, const std::string& text) {
    const std::string path = dir_ + "/" + name;
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }
  std::string error_of(const std::string& path) {
    try {
      read_joints_log(path);
    } catch (const JointsLogError& e) {
      return e.what();
    }
    return "(no error)";
  }
  // A canonical log of one right-hand frame, as the writer makes it, split into its lines.
  std::vector<std::string> canonical_lines() {
    JointsFrame f;
    f.t_ns = 8'300'000;
    for (int j = 0; j < kXrJointCount; ++j) {
      f.joints[static_cast<std::size_t>(j)].valid = true;
      f.joints[static_cast<std::size_t>(j)].p_m = {0.01 * j, 0.2, -0.03};
    }
    const std::string path = dir_ + "/canonical.csv";
    write_joints_log(path, JointsSpace::kXr, {f}, {});
    std::ifstream in(path);
    std::vector<std::string> lines;
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
  }
  std::string join(const std::vector<std::string>& lines) {
    std::string text;
    for (const auto& l : lines) text += l + "\n";
    return text;
  }
};

TEST_F(JointsLogTest, FramesRoundTripExactlyWithLostJointsAndBothHands) {
  std::vector<JointsFrame> frames(3);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    JointsFrame& f = frames[i];
    f.t_ns = static_cast<int64_t>(i / 2) * 8'333'333;  // the two hands of frame 0 share a stamp
    f.left_hand = i == 1;
    for (int j = 0; j < kXrJointCount; ++j) {
      TrackedJoint& joint = f.joints[static_cast<std::size_t>(j)];
      joint.valid = j != static_cast<int>(XrJoint::kWrist) || i == 2;
      joint.p_m = {0.1 / 3.0 * j, -0.2 + 1e-9 * static_cast<double>(i), 0.3};
      joint.has_orientation = j % 2 == 0;
      joint.q = Eigen::Quaterniond(Eigen::AngleAxisd(0.1 * j, Eigen::Vector3d(1, 2, 3).normalized()));
      joint.has_radius = j % 3 == 0;
      joint.radius_m = 0.001 * j;
    }
  }
  const std::string path = dir_ + "/both.csv";
  write_joints_log(path, JointsSpace::kCockpit, frames, {"from a test"});
  const JointsLog log = read_joints_log(path);
  EXPECT_EQ(log.space, JointsSpace::kCockpit);
  ASSERT_EQ(log.frames.size(), 3u);
  EXPECT_EQ(log.lost_joints, 2) << "the wrist of the first two rows";
  for (std::size_t i = 0; i < frames.size(); ++i) {
    EXPECT_EQ(log.frames[i].t_ns, frames[i].t_ns);
    EXPECT_EQ(log.frames[i].left_hand, frames[i].left_hand);
    for (int j = 0; j < kXrJointCount; ++j) {
      const TrackedJoint& a = frames[i].joints[static_cast<std::size_t>(j)];
      const TrackedJoint& b = log.frames[i].joints[static_cast<std::size_t>(j)];
      ASSERT_EQ(a.valid, b.valid) << i << " " << j;
      if (!a.valid) continue;
      EXPECT_EQ(a.p_m, b.p_m);
      EXPECT_EQ(a.has_orientation, b.has_orientation);
      if (a.has_orientation) {
        EXPECT_LT(a.q.angularDistance(b.q), 1e-12);
      }
      EXPECT_EQ(a.has_radius, b.has_radius);
      if (a.has_radius) {
        EXPECT_EQ(a.radius_m, b.radius_m);
      }
    }
  }
  EXPECT_FALSE(std::ifstream(path + ".partial").good());
}

TEST_F(JointsLogTest, OrientationAndRadiusColumnsAreOptional) {
  std::string header = "t_s,hand";
  std::string row = "0.5,left";
  for (int j = 0; j < kXrJointCount; ++j) {
    const std::string n(xr_joint_name(static_cast<XrJoint>(j)));
    header += "," + n + "_valid," + n + "_x_m," + n + "_y_m," + n + "_z_m";
    row += ",1,0.1,0.2,0.3";
  }
  const JointsLog log = read_joints_log(
      write("positions.csv", "# vcockpit hand joints log 1\n" + header + "\n" + row + "\n"));
  ASSERT_EQ(log.frames.size(), 1u);
  EXPECT_TRUE(log.frames[0].left_hand);
  EXPECT_EQ(log.space, JointsSpace::kXr) << "the default";
  EXPECT_FALSE(log.frames[0][XrJoint::kPalm].has_orientation);
  EXPECT_FALSE(log.frames[0][XrJoint::kIndexTip].has_radius);
  EXPECT_EQ(log.frames[0][XrJoint::kIndexTip].p_m, Eigen::Vector3d(0.1, 0.2, 0.3));
}

TEST_F(JointsLogTest, EveryBadInputNamesTheFileLineAndColumn) {
  const std::vector<std::string> good = canonical_lines();
  ASSERT_EQ(good.size(), 4u);  // version, space, header, one row
  struct Case {
    const char* what;
    std::function<void(std::vector<std::string>&)> edit;
    const char* expected;
  };
  const auto replace_field = [](std::string& line, std::size_t index, const std::string& value) {
    std::size_t start = 0;
    for (std::size_t k = 0; k < index; ++k) start = line.find(',', start) + 1;
    const std::size_t end = line.find(',', start);
    line.replace(start, end - start, value);
  };
  const std::vector<Case> cases = {
      {"no version line", [](auto& l) { l.erase(l.begin()); }, ":1: not a hand joints log"},
      {"a future version", [](auto& l) { l[0] = "# vcockpit hand joints log 2"; },
       ":1: format version '2', this build reads version 1"},
      {"an unknown space", [](auto& l) { l[1] = "# space: stage"; }, ":2: space 'stage'"},
      {"an unknown column", [](auto& l) { l[2] += ",elbow_x_m"; l[3] += ",1"; },
       ":3: column 'elbow_x_m': unknown column"},
      {"a non-number", [&](auto& l) { replace_field(l[3], 3, "abc"); },
       ":4: column 'palm_x_m': 'abc' is not a number"},
      {"a NaN position", [&](auto& l) { replace_field(l[3], 4, "nan"); },
       ":4: column 'palm_y_m': 'nan' is not finite"},
      {"a bad side", [&](auto& l) { replace_field(l[3], 1, "both"); },
       ":4: column 'hand': 'both': expected left or right"},
      {"a bad valid flag", [&](auto& l) { replace_field(l[3], 2, "yes"); },
       ":4: column 'palm_valid': 'yes': expected 1 or 0"},
      {"time going back", [](auto& l) { l.push_back(l[3]); },
       ":5: column 't_s': time 0.0083000000000000001 s does not increase for this hand"},
      {"a short row", [](auto& l) { l[3] = l[3].substr(0, l[3].find(",1,")); },
       ":4: 2 fields where the header has 236"},
      {"header only", [](auto& l) { l.pop_back(); }, ":3: header only"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    std::vector<std::string> lines = good;
    c.edit(lines);
    const std::string message = error_of(write("bad.csv", join(lines)));
    EXPECT_NE(message.find("bad.csv"), std::string::npos) << message;
    EXPECT_NE(message.find(c.expected), std::string::npos) << message;
  }
  const auto remove_field = [](std::string& line, std::size_t index) {
    std::size_t start = 0;
    for (std::size_t k = 0; k < index; ++k) start = line.find(',', start) + 1;
    line.erase(start, line.find(',', start) - start + 1);
  };
  // a required column missing; half an orientation; an optional column missing is fine
  const std::vector<std::pair<std::size_t, const char*>> removed = {
      {5, ":3: column 'palm_z_m': missing column"},
      {7, ":3: column 'palm_qw': an orientation needs all four of _qw, _qx, _qy, _qz"},
      {10, "(no error)"}};
  for (const auto& [index, expected] : removed) {
    std::vector<std::string> lines = good;
    remove_field(lines[2], index);
    remove_field(lines[3], index);
    const std::string message = error_of(write("bad.csv", join(lines)));
    EXPECT_NE(message.find(expected), std::string::npos) << message;
  }
  EXPECT_NE(error_of(dir_ + "/none.csv").find("none.csv: cannot open file"), std::string::npos);
  EXPECT_NE(error_of(write("empty.csv", "")).find("empty.csv: empty file"), std::string::npos);
}

}  // namespace
}  // namespace vcockpit::hand::tracking
