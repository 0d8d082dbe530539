#include "systems/control_frames_file.hpp"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

namespace vcockpit::systems {
namespace {

constexpr const char* kMagic = "# vcockpit control frames, version 1";

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::string field;
  std::istringstream in(s);
  while (std::getline(in, field, sep)) out.push_back(field);
  if (!s.empty() && s.back() == sep) out.emplace_back();
  return out;
}

class Reader {
 public:
  explicit Reader(const std::string& path) : path_(path) {}
  [[noreturn]] void fail(int line, const std::string& what) const {
    throw ControlFramesError(path_ + ":" + std::to_string(line) + ": " + what);
  }

 private:
  const std::string& path_;
};

}  // namespace

ControlFrames read_control_frames(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw FileError(path + ": cannot read: " + std::strerror(errno));
  const Reader r(path);
  ControlFrames out;
  out.path = path;
  std::string line;
  int n = 0;
  if (!std::getline(in, line) || line != kMagic)
    r.fail(1, "not a control frames file (its first line must be \"" + std::string(kMagic) + "\")");
  ++n;
  bool header_seen = false;
  std::vector<std::string> expected_header{"t_ns"};
  while (std::getline(in, line)) {
    ++n;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    if (line.rfind("# control: ", 0) == 0) {
      if (header_seen) r.fail(n, "a control declared after the header row");
      const std::vector<std::string> parts = split(line.substr(11), ' ');
      if (parts.size() != 3 || parts[0].empty())
        r.fail(n, "control: expected \"<name> prismatic|revolute <position>|...\"");
      ControlSpec spec;
      spec.name = parts[0];
      if (parts[1] != "prismatic" && parts[1] != "revolute")
        r.fail(n, "control " + spec.name + ": joint '" + parts[1] + "' (prismatic or revolute)");
      spec.revolute = parts[1] == "revolute";
      spec.positions = split(parts[2], '|');
      for (const std::string& p : spec.positions)
        if (p.empty()) r.fail(n, "control " + spec.name + ": an empty position name");
      if (spec.positions.empty()) r.fail(n, "control " + spec.name + ": no positions");
      out.controls.push_back(spec);
      expected_header.push_back(spec.name + ".position");
      expected_header.push_back(spec.name + ".q");
      continue;
    }
    if (line[0] == '#') continue;
    const std::vector<std::string> fields = split(line, ',');
    if (!header_seen) {
      if (fields != expected_header) {
        std::string want;
        for (const std::string& f : expected_header) want += (want.empty() ? "" : ",") + f;
        r.fail(n, "header row: expected " + want);
      }
      header_seen = true;
      continue;
    }
    if (fields.size() != expected_header.size())
      r.fail(n, std::to_string(fields.size()) + " fields, expected " +
                    std::to_string(expected_header.size()));
    ControlFrame f;
    char* end = nullptr;
    errno = 0;
    f.time_ns = std::strtoll(fields[0].c_str(), &end, 10);
    if (fields[0].empty() || *end != '\0' || errno != 0 || f.time_ns < 0)
      r.fail(n, "t_ns: '" + fields[0] + "' is not a time in ns");
    if (!out.frames.empty() && f.time_ns <= out.frames.back().time_ns)
      r.fail(n, "t_ns: " + fields[0] + " does not come after the last row's " +
                    std::to_string(out.frames.back().time_ns));
    for (std::size_t c = 0; c < out.controls.size(); ++c) {
      const std::string& pos = fields[1 + 2 * c];
      const std::string& q = fields[2 + 2 * c];
      const long p = std::strtol(pos.c_str(), &end, 10);
      if (pos.empty() || *end != '\0' || p < 0 ||
          p >= static_cast<long>(out.controls[c].positions.size()))
        r.fail(n, expected_header[1 + 2 * c] + ": '" + pos + "' is not one of its " +
                      std::to_string(out.controls[c].positions.size()) + " positions");
      const double v = std::strtod(q.c_str(), &end);
      if (q.empty() || *end != '\0' || !std::isfinite(v))
        r.fail(n, expected_header[2 + 2 * c] + ": '" + q + "' is not a finite number");
      f.position.push_back(static_cast<int32_t>(p));
      f.q.push_back(v);
    }
    out.frames.push_back(std::move(f));
  }
  if (!header_seen) r.fail(n, "no header row (t_ns,...)");
  return out;
}

ControlFramesWriter::ControlFramesWriter(const std::string& path,
                                         const std::vector<ControlSpec>& controls)
    : file_(path), controls_(controls.size()) {
  std::string text = std::string(kMagic) + "\n";
  std::string header = "t_ns";
  for (const ControlSpec& c : controls) {
    std::string positions;
    for (const std::string& p : c.positions) positions += (positions.empty() ? "" : "|") + p;
    text += "# control: " + c.name + (c.revolute ? " revolute " : " prismatic ") + positions + "\n";
    header += "," + c.name + ".position," + c.name + ".q";
  }
  file_.write(text + header + "\n");
}

void ControlFramesWriter::write(const ControlFrame& frame) {
  if (frame.position.size() != controls_ || frame.q.size() != controls_)
    throw std::invalid_argument("a control frame of another size");
  // std::to_chars with a precision writes what printf's "%.17g" does (round-trip exact), without
  // its format parsing and locking per value
  std::string row = std::to_string(frame.time_ns);
  char number[64];
  for (std::size_t c = 0; c < controls_; ++c) {
    row += ',';
    row.append(number, std::to_chars(number, number + sizeof number, frame.position[c]).ptr);
    row += ',';
    row.append(number, std::to_chars(number, number + sizeof number, frame.q[c],
                                     std::chars_format::general, 17).ptr);
  }
  row += '\n';
  file_.write(row);
}

}  // namespace vcockpit::systems
