#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "glove_driver/glove/glove_log.hpp"

namespace vcockpit::glove {
namespace {

[[noreturn]] void io_fail(const std::string& path, const std::string& what) {
  throw GloveLogError(path + ": " + what + ": " + std::strerror(errno));
}

// %.17g round-trips every double exactly.
void write_line(std::FILE* f, const GloveSample& s) {
  std::fprintf(f, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g", ns_to_log_seconds(s.t_ns),
               s.p_MT_m.x(), s.p_MT_m.y(), s.p_MT_m.z(), s.q_MT.w(), s.q_MT.x(), s.q_MT.y(),
               s.q_MT.z());
  for (double q : s.joints_rad) std::fprintf(f, ",%.17g", q);
  std::fputc('\n', f);
}

}  // namespace

std::string canonical_header() {
  std::string header = "t_s,x_m,y_m,z_m,qw,qx,qy,qz";
  for (int j = 0; j < physics::kJointCount; ++j) {
    header += ",";
    header += physics::joint_name(static_cast<physics::Joint>(j));
    header += "_rad";
  }
  return header;
}

GloveLogWriter::GloveLogWriter(const std::string& path, bool left_hand,
                               const std::vector<std::string>& comments)
    : path_(path), partial_path_(path + ".partial") {
  file_ = std::fopen(partial_path_.c_str(), "w");
  if (!file_) io_fail(partial_path_, "cannot create");
  std::fprintf(file_, "# vcockpit glove log\n# hand: %s\n", left_hand ? "left" : "right");
  for (const auto& c : comments) std::fprintf(file_, "# %s\n", c.c_str());
  std::fprintf(file_, "%s\n", canonical_header().c_str());
}

GloveLogWriter::~GloveLogWriter() {
  if (file_) {
    std::fclose(file_);
    std::remove(partial_path_.c_str());
  }
}

void GloveLogWriter::append(const GloveSample& sample) {
  write_line(file_, sample);
  ++count_;
}

void GloveLogWriter::commit() {
  if (!file_) throw GloveLogError(path_ + ": already committed");
  const bool ok = std::fflush(file_) == 0 && fsync(fileno(file_)) == 0 && !std::ferror(file_);
  std::fclose(file_);
  file_ = nullptr;
  if (!ok) {
    std::remove(partial_path_.c_str());
    io_fail(partial_path_, "write failed");
  }
  if (std::rename(partial_path_.c_str(), path_.c_str()) != 0) {
    std::remove(partial_path_.c_str());
    io_fail(path_, "cannot rename the finished log into place");
  }
}

void write_glove_log(const std::string& path, const std::vector<GloveSample>& samples,
                     bool left_hand, const std::vector<std::string>& comments) {
  GloveLogWriter writer(path, left_hand, comments);
  for (const auto& s : samples) writer.append(s);
  writer.commit();
}

}  // namespace vcockpit::glove
