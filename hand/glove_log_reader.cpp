#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <sstream>

#include "common/pose.hpp"
#include "hand/csv_line.hpp"
#include "hand/glove_log.hpp"

namespace vcockpit::hand {
namespace {

// What a header column means.
enum class Field { kTime, kX, kY, kZ, kQw, kQx, kQy, kQz, kPsi, kTheta, kGamma, kJoint };

struct Column {
  std::string name;
  Field field;
  double to_rad = 1.0;  // unit factor for angles
  int joint = -1;
};

// Splits "thumb_mcp_deg" into base name and unit factor; false if no known unit suffix.
bool split_unit(const std::string& name, std::string& base, double& to_rad) {
  auto ends_with = [&](const char* suffix) {
    const std::string s(suffix);
    return name.size() > s.size() && name.compare(name.size() - s.size(), s.size(), s) == 0;
  };
  if (ends_with("_rad")) {
    base = name.substr(0, name.size() - 4);
    to_rad = 1.0;
    return true;
  }
  if (ends_with("_deg")) {
    base = name.substr(0, name.size() - 4);
    to_rad = deg_to_rad(1.0);
    return true;
  }
  return false;
}

class Reader {
 public:
  Reader(const std::string& path, const hand::HandModel& hand) : path_(path), hand_(hand) {
    log_.path = path;
  }

  GloveLog read() {
    std::ifstream in(path_, std::ios::binary);
    if (!in) throw GloveLogError(path_ + ": cannot open file");
    std::string line;
    bool have_header = false;
    while (std::getline(in, line)) {
      ++line_no_;
      const bool ends_with_newline = !in.eof();
      const std::string text = trim(line);
      if (text.empty()) continue;
      if (text[0] == '#') {
        read_comment(text);
        continue;
      }
      if (!have_header) {
        read_header(text);
        have_header = true;
        continue;
      }
      read_row(text, ends_with_newline);
    }
    if (!have_header) throw GloveLogError(path_ + ": empty log (no header line)");
    if (log_.samples.empty() && log_.dropped_samples > 0) {
      throw GloveLogError(path_ + ": every one of the " + std::to_string(log_.dropped_samples) +
                          " samples is a dropout (all nan), the log has no valid sample");
    }
    if (log_.samples.empty()) {
      throw GloveLogError(path_ + ":" + std::to_string(header_line_) +
                          ": header only, the log has no samples");
    }
    return std::move(log_);
  }

  // The comment lines before the header only: whose hand the log is.
  bool read_side() {
    std::ifstream in(path_, std::ios::binary);
    if (!in) throw GloveLogError(path_ + ": cannot open file");
    for (std::string line; std::getline(in, line);) {
      ++line_no_;
      const std::string text = trim(line);
      if (text.empty()) continue;
      if (text[0] != '#') break;
      read_comment(text);
    }
    return log_.left_hand;
  }

 private:
  [[noreturn]] void fail(const std::string& column, const std::string& message) const {
    std::ostringstream msg;
    msg << path_ << ':' << line_no_ << ": ";
    if (!column.empty()) msg << "column '" << column << "': ";
    msg << message;
    throw GloveLogError(msg.str());
  }

  void read_comment(const std::string& text) {
    std::string body = trim(text.substr(1));
    log_.comments.push_back(body);
    if (body.rfind("hand:", 0) == 0) {
      const std::string side = trim(body.substr(5));
      if (side == "left") {
        log_.left_hand = true;
      } else if (side == "right") {
        log_.left_hand = false;
      } else {
        fail("", "hand must be 'left' or 'right', found '" + side + "'");
      }
    }
  }

  void read_header(const std::string& text) {
    header_line_ = line_no_;
    std::array<bool, hand::kJointCount> joint_seen{};
    for (const std::string& name : split_csv(text)) {
      for (const auto& c : columns_) {
        if (c.name == name) fail(name, "column appears twice");
      }
      columns_.push_back(classify(name));
      if (columns_.back().field == Field::kJoint) joint_seen[columns_.back().joint] = true;
    }
    require_columns();
    for (int j = 0; j < hand::kJointCount; ++j) {
      if (!joint_seen[j]) {
        log_.missing_joints.emplace_back(hand::joint_name(static_cast<hand::Joint>(j)));
      }
    }
    log_.counts.missing_columns = log_.missing_joints.size();
  }

  Column classify(const std::string& name) const {
    static const std::pair<const char*, Field> kFixed[] = {
        {"t_s", Field::kTime}, {"x_m", Field::kX}, {"y_m", Field::kY}, {"z_m", Field::kZ},
        {"qw", Field::kQw},    {"qx", Field::kQx}, {"qy", Field::kQy}, {"qz", Field::kQz}};
    for (const auto& [fixed, field] : kFixed) {
      if (name == fixed) return {name, field};
    }
    std::string base;
    double to_rad = 1.0;
    if (split_unit(name, base, to_rad)) {
      if (base == "psi") return {name, Field::kPsi, to_rad};
      if (base == "theta") return {name, Field::kTheta, to_rad};
      if (base == "gamma") return {name, Field::kGamma, to_rad};
      const int joint = hand::joint_index(base);
      if (joint >= 0) return {name, Field::kJoint, to_rad, joint};
    }
    fail(name, "unknown column (expected t_s, x_m, y_m, z_m, qw..qz or psi/theta/gamma, and "
               "joint names such as index_mcp with a _rad or _deg suffix)");
  }

  bool has(Field f) const {
    for (const auto& c : columns_) {
      if (c.field == f) return true;
    }
    return false;
  }

  void require_columns() {
    for (auto [field, name] : {std::pair{Field::kTime, "t_s"}, {Field::kX, "x_m"},
                               {Field::kY, "y_m"}, {Field::kZ, "z_m"}}) {
      if (!has(field)) fail(name, "required column is missing");
    }
    const int quat = has(Field::kQw) + has(Field::kQx) + has(Field::kQy) + has(Field::kQz);
    const int euler = has(Field::kPsi) + has(Field::kTheta) + has(Field::kGamma);
    if (quat == 4 && euler == 0) {
      quaternion_ = true;
    } else if (euler == 3 && quat == 0) {
      quaternion_ = false;
    } else {
      fail("", "wrist orientation needs either qw,qx,qy,qz or psi,theta,gamma (with _rad or "
               "_deg), not a mix or a partial set");
    }
  }

  double parse_number(const std::string& field, const std::string& column) const {
    if (field.empty()) fail(column, "empty field");
    char* end = nullptr;
    const double value = std::strtod(field.c_str(), &end);
    if (end != field.c_str() + field.size()) fail(column, "not a number: '" + field + "'");
    if (!std::isfinite(value)) fail(column, "not a finite number: '" + field + "'");
    return value;
  }

  void read_row(const std::string& text, bool ends_with_newline) {
    const auto fields = split_csv(text);
    if (fields.size() != columns_.size()) {
      if (!ends_with_newline && fields.size() < columns_.size()) {
        fail("", "truncated last line: " + std::to_string(fields.size()) + " of " +
                     std::to_string(columns_.size()) + " fields");
      }
      fail("", "expected " + std::to_string(columns_.size()) + " fields, found " +
                   std::to_string(fields.size()));
    }
    if (is_dropout(fields)) {
      read_dropout(fields);
      return;
    }
    GloveSample s;
    s.joints_rad = hand_.rest_pose();
    double q[4] = {1, 0, 0, 0};
    double euler[3] = {0, 0, 0};
    double t_s = 0;
    for (std::size_t i = 0; i < fields.size(); ++i) {
      const Column& c = columns_[i];
      const double v = parse_number(fields[i], c.name);
      switch (c.field) {
        case Field::kTime: t_s = v; break;
        case Field::kX: s.p_MT_m.x() = v; break;
        case Field::kY: s.p_MT_m.y() = v; break;
        case Field::kZ: s.p_MT_m.z() = v; break;
        case Field::kQw: q[0] = v; break;
        case Field::kQx: q[1] = v; break;
        case Field::kQy: q[2] = v; break;
        case Field::kQz: q[3] = v; break;
        case Field::kPsi: euler[0] = v * c.to_rad; break;
        case Field::kTheta: euler[1] = v * c.to_rad; break;
        case Field::kGamma: euler[2] = v * c.to_rad; break;
        case Field::kJoint: s.joints_rad[c.joint] = clamp_joint(c, v * c.to_rad); break;
      }
    }
    s.t_ns = log_seconds_to_ns(t_s);
    check_time_increases(s.t_ns, fields);
    last_t_ns_ = s.t_ns;
    have_time_ = true;
    if (quaternion_) {
      s.q_MT = Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
      // kept exactly as written (a replay publishes what the log says); only checked
      if (std::abs(s.q_MT.norm() - 1.0) > 1e-3) fail("qw", "wrist quaternion is not unit length");
    } else {
      s.q_MT = Eigen::Quaterniond(
          rotation_from_euler(hand_.tracker.euler_axes, euler[0], euler[1], euler[2]));
    }
    log_.samples.push_back(s);
  }

  // Every field but t_s is "nan" (any case): the device's sample without valid data.
  bool is_dropout(const std::vector<std::string>& fields) const {
    auto lower = [](char c) { return std::tolower(static_cast<unsigned char>(c)); };
    for (std::size_t i = 0; i < fields.size(); ++i) {
      if (columns_[i].field == Field::kTime) continue;
      const std::string& f = fields[i];
      if (f.size() != 3 || lower(f[0]) != 'n' || lower(f[1]) != 'a' || lower(f[2]) != 'n') {
        return false;
      }
    }
    return fields.size() > 1;
  }

  void read_dropout(const std::vector<std::string>& fields) {
    const std::size_t t = time_column();
    const int64_t t_ns = log_seconds_to_ns(parse_number(fields[t], columns_[t].name));
    check_time_increases(t_ns, fields);
    last_t_ns_ = t_ns;
    have_time_ = true;
    ++log_.counts.rejected_nonfinite;  // as the sample gate counts such a sample on the topic
    if (log_.dropped_samples++ == 0) {
      log_.first_dropout = path_ + ":" + std::to_string(line_no_) +
                           ": a dropout (every value nan), skipped";
    }
  }

  // Dropout rows keep their stamps, so time must increase over them too.
  void check_time_increases(int64_t t_ns, const std::vector<std::string>& fields) const {
    if (have_time_ && t_ns <= last_t_ns_) {
      fail("t_s", "time does not increase (" + fields[time_column()] + " after " +
                      std::to_string(ns_to_log_seconds(last_t_ns_)) + " s)");
    }
  }

  std::size_t time_column() const {
    for (std::size_t i = 0; i < columns_.size(); ++i) {
      if (columns_[i].field == Field::kTime) return i;
    }
    return 0;
  }

  double clamp_joint(const Column& c, double value_rad) {
    const auto& range = hand_.joints[c.joint];
    if (value_rad >= range.min_rad && value_rad <= range.max_rad) return value_rad;
    if (log_.counts.clamped++ == 0) {
      log_.first_clamp = path_ + ":" + std::to_string(line_no_) + ": column '" + c.name +
                         "' beyond the joint limits, clamped";
    }
    return std::clamp(value_rad, range.min_rad, range.max_rad);
  }

  std::string path_;
  const hand::HandModel& hand_;
  GloveLog log_;
  std::vector<Column> columns_;
  bool quaternion_ = true;
  int line_no_ = 0;
  int header_line_ = 0;
  int64_t last_t_ns_ = 0;  // the previous row's stamp, dropouts included
  bool have_time_ = false;
};

}  // namespace

GloveLog read_glove_log(const std::string& path, const hand::HandModel& hand) {
  return Reader(path, hand).read();
}

bool glove_log_left_hand(const std::string& path) {
  static const hand::HandModel kNoModel{};  // the comment lines need none
  return Reader(path, kNoModel).read_side();
}

std::vector<std::string> glove_log_warnings(const GloveLog& log) {
  std::vector<std::string> out;
  if (!log.missing_joints.empty()) {
    std::string names;
    for (const auto& n : log.missing_joints) names += (names.empty() ? "" : ", ") + n;
    out.push_back(log.path + ": no column for " + std::to_string(log.missing_joints.size()) +
                  " joint(s), using the rest pose: " + names);
  }
  if (log.counts.clamped > 0) {
    out.push_back(log.path + ": " + std::to_string(log.counts.clamped) +
                  " joint value(s) beyond the limits were clamped; first: " + log.first_clamp);
  }
  return out;
}

}  // namespace vcockpit::hand
