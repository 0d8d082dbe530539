#pragma once
// Glove logs: plain CSV that users can make and read.
//
//   # vcockpit glove log            <- '#' lines are comments, allowed anywhere
//   # hand: right                   <- recognised: hand side (right by default)
//   t_s,x_m,y_m,z_m,qw,qx,qy,qz,thumb_rotation_rad,...,wrist_yaw_rad
//   0,0.1,0.3,0.9,1,0,0,0,0.1,...
//
// Columns: t_s (strictly increasing); wrist position x_m,y_m,z_m in the tracker frame M; wrist
// orientation either qw,qx,qy,qz (unit quaternion) or psi,theta,gamma with _rad or _deg (Euler
// convention from hand.yaml tracker.euler); joint columns named by the CyberGlove order
// (hand_joints.hpp) with _rad or _deg. Missing joint columns take the hand's rest pose and are
// reported once; an unknown or repeated column is an error. Values beyond a joint's limits are
// clamped to the limit and counted (a glove reads a little past a calibrated range all the
// time; rejecting the whole log for it would be useless). A row whose every field but t_s is
// `nan` is a dropout: the device sent a sample without valid data (a tracker that lost its fix,
// a glove packet that failed its checksum). It is skipped and counted, like the sample gate
// rejects such a sample on the topic. Everything else that is wrong — a non-numeric field, a
// NaN/Inf among numbers, time not increasing, a short or truncated line, an empty or
// header-only file, a log of dropouts only — is an error naming the file, the line and the column.

#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/atomic_file.hpp"
#include "hand/glove_sample.hpp"
#include "hand/hand_model.hpp"
#include "hand/input_counts.hpp"

namespace vcockpit::hand {

class GloveLogError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct GloveLog {
  std::string path;
  bool left_hand = false;
  std::vector<std::string> comments;  // comment lines without the leading '#' and space
  std::vector<GloveSample> samples;
  std::vector<std::string> missing_joints;  // channels that took the rest pose
  std::string first_clamp;                  // "file:line: column ..." of the first, for the log
  // what reading did to the values: `clamped` joint values, `missing_columns` (= missing_joints)
  InputCounts counts;
  int dropped_samples = 0;                  // all-`nan` rows (dropouts), skipped
  std::string first_dropout;                // "file:line: ..." of the first, for the log
};

// Reads and validates a whole log. Throws GloveLogError.
GloveLog read_glove_log(const std::string& path, const hand::HandModel& hand);

// Whose hand a log is (its `# hand:` comment line, read without the rest of the file): true for
// a left hand; false for a right one or a log that does not say. Throws GloveLogError when the
// file cannot be opened or the side is neither left nor right (file:line).
bool glove_log_left_hand(const std::string& path);

// The warnings a node logs once after reading a log: missing columns (named) and clamped values
// (counted, the first one located). Empty for a clean log.
std::vector<std::string> glove_log_warnings(const GloveLog& log);

// Writes a log atomically: to "<path>.partial", then renamed over <path>. The columns are the
// canonical ones (t_s, position, quaternion, all 22 joints in rad), full double precision, so
// reading it back gives identical values. Throws GloveLogError on I/O failure.
void write_glove_log(const std::string& path, const std::vector<GloveSample>& samples,
                     bool left_hand, const std::vector<std::string>& comments);

// Streaming form of write_glove_log for recording: lines go to "<path>.partial" as they come
// (AtomicFile); commit() renames into place. Destroyed without commit() (error, exception), it
// removes the partial file, so an interrupted recording never leaves a corrupt log.
class GloveLogWriter {
 public:
  GloveLogWriter(const std::string& path, bool left_hand, const std::vector<std::string>& comments);

  void append(const GloveSample& sample);
  // A dropout row: t_s, then `nan` in every other column (read back as a skipped, counted row).
  void append_dropout(int64_t t_ns);
  // "# text" where the log stands (e.g. after the samples: what the recording lost)
  void append_comment(const std::string& text);
  void commit();  // throws GloveLogError on failure
  std::size_t count() const { return count_; }

 private:
  AtomicFile file_;
  std::size_t count_ = 0;
};

// The canonical header line (without newline).
std::string canonical_header();

}  // namespace vcockpit::hand
