#pragma once
// control_frames.csv: the controls at every systems step of a run. The physics writes it beside
// trajectories.csv (offline, and a lockstep node with --out); systems_node --offline reads it, so
// the systems see offline exactly the frames cockpit/control_frame carries in a rig.
//
//   # vcockpit control frames, version 1
//   # control: <name> prismatic|revolute <position>|<position>|...     one per control, in order
//   t_ns,<name>.position,<name>.q,...                                   the header row
//   10000000,0,0,...                                                    one row a frame
//
// q in SI units (m or rad) printed with 17 significant digits, so a read gives the bits written.
// Rows go up in time. Every error names the file, the line and the field.

#include <stdexcept>
#include <string>
#include <vector>

#include "common/atomic_file.hpp"
#include "systems/system_model.hpp"
#include "systems/systems_engine.hpp"

namespace vcockpit::systems {

class ControlFramesError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ControlFrames {
  std::string path;
  std::vector<ControlSpec> controls;
  std::vector<ControlFrame> frames;
};

// Throws ControlFramesError "path:line: field: message" (FileError when unreadable).
ControlFrames read_control_frames(const std::string& path);

class ControlFramesWriter {
 public:
  // The header now; the file appears under `path` on commit() (AtomicFile).
  ControlFramesWriter(const std::string& path, const std::vector<ControlSpec>& controls);
  void write(const ControlFrame& frame);
  void commit() { file_.commit(); }

 private:
  AtomicFile file_;
  std::size_t controls_;
};

}  // namespace vcockpit::systems
