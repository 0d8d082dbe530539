#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "hand/csv_line.hpp"
#include "hand/glove_sample.hpp"
#include "hand/tracking/joints_log.hpp"

namespace vcockpit::hand::tracking {
namespace {

// The fields of one joint, in the order the writer puts them.
enum Part { kValid, kX, kY, kZ, kQw, kQx, kQy, kQz, kRadius, kPartCount };
constexpr const char* kPartSuffix[kPartCount] = {"_valid", "_x_m",  "_y_m",  "_z_m",     "_qw",
                                                  "_qx",    "_qy",   "_qz",   "_radius_m"};

class Reader {
 public:
  explicit Reader(const std::string& path) : path_(path) { log_.path = path; }

  JointsLog read() {
    std::ifstream in(path_, std::ios::binary);
    if (!in) throw JointsLogError(path_ + ": cannot open file");
    std::string line;
    bool have_version = false, have_header = false;
    while (std::getline(in, line)) {
      ++line_no_;
      const bool ends_with_newline = !in.eof();
      const std::string text = trim(line);
      if (text.empty()) continue;
      if (!have_version) {
        read_version(text);
        have_version = true;
        continue;
      }
      if (text[0] == '#') {
        read_comment(text, have_header);
        continue;
      }
      if (!have_header) {
        read_header(text);
        have_header = true;
        continue;
      }
      read_row(text, ends_with_newline);
    }
    if (!have_version) throw JointsLogError(path_ + ": empty file (no '# vcockpit hand joints log' line)");
    if (!have_header) throw JointsLogError(path_ + ": no header line");
    if (log_.frames.empty())
      throw JointsLogError(path_ + ":" + std::to_string(header_line_) + ": header only, the log has no frames");
    return std::move(log_);
  }

 private:
  [[noreturn]] void fail(const std::string& column, const std::string& message) const {
    std::ostringstream msg;
    msg << path_ << ':' << line_no_ << ": ";
    if (!column.empty()) msg << "column '" << column << "': ";
    msg << message;
    throw JointsLogError(msg.str());
  }

  void read_version(const std::string& text) {
    static const std::string kTag = "# vcockpit hand joints log";
    if (text.rfind(kTag, 0) != 0)
      fail("", "not a hand joints log: the first line must be '" + kTag + " " +
                   std::to_string(kJointsLogVersion) + "'");
    const std::string version = trim(text.substr(kTag.size()));
    if (version != std::to_string(kJointsLogVersion))
      fail("", "format version '" + version + "', this build reads version " +
                   std::to_string(kJointsLogVersion));
  }

  void read_comment(const std::string& text, bool after_header) {
    std::string body = trim(text.substr(1));
    log_.comments.push_back(body);
    if (after_header || body.rfind("space:", 0) != 0) return;
    const std::string value = trim(body.substr(6));
    if (value == "xr") {
      log_.space = JointsSpace::kXr;
    } else if (value == "cockpit") {
      log_.space = JointsSpace::kCockpit;
    } else {
      fail("", "space '" + value + "': expected xr or cockpit");
    }
  }

  void read_header(const std::string& text) {
    header_line_ = line_no_;
    columns_ = split_csv(text);
    std::map<std::string, int> seen;
    for (std::size_t i = 0; i < columns_.size(); ++i) {
      const std::string& name = columns_[i];
      if (!seen.emplace(name, static_cast<int>(i)).second) fail(name, "repeated column");
      if (name == "t_s") {
        time_col_ = static_cast<int>(i);
        continue;
      }
      if (name == "hand") {
        hand_col_ = static_cast<int>(i);
        continue;
      }
      int joint = -1, part = -1;
      for (int p = 0; p < kPartCount && joint < 0; ++p) {
        const std::string suffix = kPartSuffix[p];
        if (name.size() <= suffix.size() || name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0)
          continue;
        joint = xr_joint_index(name.substr(0, name.size() - suffix.size()));
        part = p;
      }
      if (joint < 0) fail(name, "unknown column (expected t_s, hand, or <joint>_valid, _x_m, _y_m, _z_m, _qw.._qz, _radius_m of an OpenXR hand joint)");
      col_[static_cast<std::size_t>(joint)][static_cast<std::size_t>(part)] = static_cast<int>(i);
    }
    if (time_col_ < 0) fail("t_s", "missing column");
    if (hand_col_ < 0) fail("hand", "missing column");
    for (int j = 0; j < kXrJointCount; ++j) {
      const auto& c = col_[static_cast<std::size_t>(j)];
      const std::string joint(xr_joint_name(static_cast<XrJoint>(j)));
      for (int p : {kValid, kX, kY, kZ})
        if (c[static_cast<std::size_t>(p)] < 0) fail(joint + kPartSuffix[p], "missing column");
      const int quaternion = (c[kQw] >= 0) + (c[kQx] >= 0) + (c[kQy] >= 0) + (c[kQz] >= 0);
      if (quaternion != 0 && quaternion != 4)
        fail(joint + "_qw", "an orientation needs all four of _qw, _qx, _qy, _qz");
    }
  }

  double number(const std::vector<std::string>& fields, int col) const {
    const std::string& f = fields[static_cast<std::size_t>(col)];
    const std::string& name = columns_[static_cast<std::size_t>(col)];
    if (f.empty()) fail(name, "empty field");
    double value = 0.0;
    const auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), value);
    if (ec != std::errc() || end != f.data() + f.size()) fail(name, "'" + f + "' is not a number");
    if (!std::isfinite(value)) fail(name, "'" + f + "' is not finite");
    return value;
  }

  void read_row(const std::string& text, bool ends_with_newline) {
    const std::vector<std::string> fields = split_csv(text);
    if (fields.size() != columns_.size()) {
      fail("", std::to_string(fields.size()) + " fields where the header has " +
                   std::to_string(columns_.size()) + (ends_with_newline ? "" : " (a truncated last line?)"));
    }
    JointsFrame frame;
    const double t_s = number(fields, time_col_);
    frame.t_ns = log_seconds_to_ns(t_s);
    const std::string& side = fields[static_cast<std::size_t>(hand_col_)];
    if (side == "left") {
      frame.left_hand = true;
    } else if (side != "right") {
      fail("hand", "'" + side + "': expected left or right");
    }
    int64_t& last_ns = last_ns_[frame.left_hand ? 1 : 0];
    if (frame.t_ns <= last_ns) fail("t_s", "time " + fields[static_cast<std::size_t>(time_col_)] + " s does not increase for this hand");
    last_ns = frame.t_ns;
    for (int j = 0; j < kXrJointCount; ++j) {
      const auto& c = col_[static_cast<std::size_t>(j)];
      TrackedJoint& joint = frame.joints[static_cast<std::size_t>(j)];
      const std::string& valid = fields[static_cast<std::size_t>(c[kValid])];
      if (valid == "0") {
        ++log_.lost_joints;
        continue;
      }
      if (valid != "1") fail(columns_[static_cast<std::size_t>(c[kValid])], "'" + valid + "': expected 1 or 0");
      joint.valid = true;
      joint.p_m = {number(fields, c[kX]), number(fields, c[kY]), number(fields, c[kZ])};
      if (c[kQw] >= 0 && !fields[static_cast<std::size_t>(c[kQw])].empty()) {
        Eigen::Quaterniond q(number(fields, c[kQw]), number(fields, c[kQx]), number(fields, c[kQy]),
                             number(fields, c[kQz]));
        if (std::abs(q.norm() - 1.0) > 1e-3)
          fail(columns_[static_cast<std::size_t>(c[kQw])], "orientation of length " + std::to_string(q.norm()) + ", not a unit quaternion");
        joint.q = q.normalized();
        joint.has_orientation = true;
      }
      if (c[kRadius] >= 0 && !fields[static_cast<std::size_t>(c[kRadius])].empty()) {
        joint.radius_m = number(fields, c[kRadius]);
        if (joint.radius_m < 0.0) fail(columns_[static_cast<std::size_t>(c[kRadius])], "negative radius");
        joint.has_radius = true;
      }
    }
    log_.frames.push_back(frame);
  }

  std::string path_;
  JointsLog log_;
  int line_no_ = 0;
  int header_line_ = 0;
  std::vector<std::string> columns_;
  int time_col_ = -1, hand_col_ = -1;
  std::array<std::array<int, kPartCount>, kXrJointCount> col_ = [] {
    std::array<std::array<int, kPartCount>, kXrJointCount> c{};
    for (auto& joint : c) joint.fill(-1);
    return c;
  }();
  std::array<int64_t, 2> last_ns_ = {INT64_MIN, INT64_MIN};
};

}  // namespace

JointsLog read_joints_log(const std::string& path) { return Reader(path).read(); }

const char* joints_space_name(JointsSpace space) {
  return space == JointsSpace::kCockpit ? "cockpit" : "xr";
}

}  // namespace vcockpit::hand::tracking
