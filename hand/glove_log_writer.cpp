#include "hand/glove_log.hpp"

namespace vcockpit::hand {
namespace {

// %.17g round-trips every double exactly.
void write_line(std::FILE* f, const GloveSample& s) {
  std::fprintf(f, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g", ns_to_log_seconds(s.t_ns),
               s.p_MT_m.x(), s.p_MT_m.y(), s.p_MT_m.z(), s.q_MT.w(), s.q_MT.x(), s.q_MT.y(),
               s.q_MT.z());
  for (double q : s.joints_rad) std::fprintf(f, ",%.17g", q);
  std::fputc('\n', f);
}

AtomicFile open_log(const std::string& path) {
  try {
    return AtomicFile(path);
  } catch (const FileError& e) {
    throw GloveLogError(e.what());
  }
}

}  // namespace

std::string canonical_header() {
  std::string header = "t_s,x_m,y_m,z_m,qw,qx,qy,qz";
  for (int j = 0; j < hand::kJointCount; ++j) {
    header += ",";
    header += hand::joint_name(static_cast<hand::Joint>(j));
    header += "_rad";
  }
  return header;
}

GloveLogWriter::GloveLogWriter(const std::string& path, bool left_hand,
                               const std::vector<std::string>& comments)
    : file_(open_log(path)) {
  std::fprintf(file_.get(), "# vcockpit glove log\n# hand: %s\n", left_hand ? "left" : "right");
  for (const auto& c : comments) std::fprintf(file_.get(), "# %s\n", c.c_str());
  std::fprintf(file_.get(), "%s\n", canonical_header().c_str());
}

void GloveLogWriter::append(const GloveSample& sample) {
  write_line(file_.get(), sample);
  ++count_;
}

void GloveLogWriter::append_dropout(int64_t t_ns) {
  std::fprintf(file_.get(), "%.17g", ns_to_log_seconds(t_ns));
  for (int i = 0; i < 7 + hand::kJointCount; ++i) std::fputs(",nan", file_.get());
  std::fputc('\n', file_.get());
  ++count_;
}

void GloveLogWriter::append_comment(const std::string& text) {
  std::fprintf(file_.get(), "# %s\n", text.c_str());
}

void GloveLogWriter::commit() {
  try {
    file_.commit();
  } catch (const FileError& e) {
    throw GloveLogError(e.what());
  }
}

void write_glove_log(const std::string& path, const std::vector<GloveSample>& samples,
                     bool left_hand, const std::vector<std::string>& comments) {
  GloveLogWriter writer(path, left_hand, comments);
  for (const auto& s : samples) writer.append(s);
  writer.commit();
}

}  // namespace vcockpit::hand
