#include <cinttypes>
#include <cstdio>

#include "common/atomic_file.hpp"
#include "hand/glove_sample.hpp"
#include "hand/tracking/joints_log.hpp"

namespace vcockpit::hand::tracking {
namespace {

void add_number(std::string& line, double value) {
  char text[32];
  std::snprintf(text, sizeof text, ",%.17g", value);
  line += text;
}

}  // namespace

void write_joints_log(const std::string& path, JointsSpace space,
                      const std::vector<JointsFrame>& frames,
                      const std::vector<std::string>& comments) {
  try {
    AtomicFile file(path);
    std::string text = "# vcockpit hand joints log " + std::to_string(kJointsLogVersion) + "\n";
    text += std::string("# space: ") + joints_space_name(space) + "\n";
    for (const std::string& c : comments) text += "# " + c + "\n";
    text += "t_s,hand";
    for (int j = 0; j < kXrJointCount; ++j) {
      const std::string n(xr_joint_name(static_cast<XrJoint>(j)));
      text += "," + n + "_valid," + n + "_x_m," + n + "_y_m," + n + "_z_m," + n + "_qw," + n +
              "_qx," + n + "_qy," + n + "_qz," + n + "_radius_m";
    }
    text += "\n";
    file.write(text);
    for (const JointsFrame& f : frames) {
      char stamp[48];
      std::snprintf(stamp, sizeof stamp, "%.17g,%s", ns_to_log_seconds(f.t_ns), f.left_hand ? "left" : "right");
      std::string line = stamp;
      for (const TrackedJoint& j : f.joints) {
        if (!j.valid) {
          line += ",0,,,,,,,,";
          continue;
        }
        line += ",1";
        for (int k = 0; k < 3; ++k) add_number(line, j.p_m[k]);
        if (j.has_orientation) {
          add_number(line, j.q.w());
          add_number(line, j.q.x());
          add_number(line, j.q.y());
          add_number(line, j.q.z());
        } else {
          line += ",,,,";
        }
        if (j.has_radius) {
          add_number(line, j.radius_m);
        } else {
          line += ",";
        }
      }
      line += "\n";
      file.write(line);
    }
    file.commit();
  } catch (const FileError& e) {
    throw JointsLogError(e.what());
  }
}

}  // namespace vcockpit::hand::tracking
