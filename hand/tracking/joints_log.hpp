#pragma once
// Hand-joints logs: what a hand tracker saw, frame by frame, as plain CSV that users can make and
// read. The joint set is OpenXR's (xr_hand_joints.hpp).
//
//   # vcockpit hand joints log 1         <- required first line: the format and its version
//   # space: xr                          <- recognised: the frame of every position (below)
//   t_s,hand,palm_valid,palm_x_m,palm_y_m,palm_z_m,palm_qw,...,little_tip_radius_m
//   0.0083,right,1,0.071,0.185,0.012,0.98,...
//
// One row is one hand in one frame: t_s (seconds; strictly increasing for each hand, the two
// hands of a frame may share it), hand (left or right), then for each of the 26 joints:
//   <joint>_valid         1 tracked, 0 not (a tracker loses joints: their fields may be empty)
//   <joint>_x_m, _y_m, _z_m                      position, required columns
//   <joint>_qw, _qx, _qy, _qz                    orientation, optional (all four or none)
//   <joint>_radius_m                             radius, optional
// Space `xr` (the default): x right, y up, z toward the user, as OpenXR's reference spaces and
// the Leap Motion device; space `cockpit`: the cockpit's frame G (x forward, y left, z up).
// '#' lines are comments anywhere. A valid joint's numbers must be finite (a quaternion of unit
// length within 1e-3, normalised; a radius not negative). Anything wrong — an unknown, repeated
// or missing column, a non-number, time not increasing, a short line, an unknown version, an
// empty or header-only file — is an error naming the file, the line and the column.

#include <Eigen/Geometry>

#include <array>
#include <stdexcept>
#include <string>
#include <vector>

#include "hand/tracking/xr_hand_joints.hpp"

namespace vcockpit::hand::tracking {

inline constexpr int kJointsLogVersion = 1;

class JointsLogError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class JointsSpace { kXr, kCockpit };

struct TrackedJoint {
  bool valid = false;
  Eigen::Vector3d p_m = Eigen::Vector3d::Zero();
  bool has_orientation = false;
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  bool has_radius = false;
  double radius_m = 0.0;
};

struct JointsFrame {
  int64_t t_ns = 0;
  bool left_hand = false;
  std::array<TrackedJoint, kXrJointCount> joints{};

  const TrackedJoint& operator[](XrJoint j) const { return joints[static_cast<std::size_t>(j)]; }
  TrackedJoint& operator[](XrJoint j) { return joints[static_cast<std::size_t>(j)]; }
};

struct JointsLog {
  std::string path;
  JointsSpace space = JointsSpace::kXr;
  std::vector<std::string> comments;  // comment lines without the leading '#' and space
  std::vector<JointsFrame> frames;    // in file order
  int lost_joints = 0;                // joints marked not valid, over all frames
};

// Reads and validates a whole log. Throws JointsLogError.
JointsLog read_joints_log(const std::string& path);

// Writes a log atomically ("<path>.partial", renamed over <path>): every column, full double
// precision, so reading it back gives identical values; a joint without orientation or radius
// leaves those fields empty. Throws JointsLogError on I/O failure.
void write_joints_log(const std::string& path, JointsSpace space,
                      const std::vector<JointsFrame>& frames,
                      const std::vector<std::string>& comments);

const char* joints_space_name(JointsSpace space);

}  // namespace vcockpit::hand::tracking
