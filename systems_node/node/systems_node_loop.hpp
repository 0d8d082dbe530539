#pragma once
// systems_node on DDS: the aircraft's systems in lockstep with the physics' time.
//   reads    cockpit/control_info (the scene's controls, to bind the model's names)
//            cockpit/control_frame (the controls every period of world time: input and clock)
//            cockpit/failure_command (an instructor inserts or clears a failure)
//   writes   cockpit/systems_info once, cockpit/systems_state after every step,
//            cockpit/systems_event for each change, cockpit/failure_ack, cockpit/node_status
// Frames that come before every control's info are kept (at most 10 s of them) and taken once
// the model is bound. With --checkpoint the state is saved every checkpoint_every_s of simulated
// time and at stop; --resume starts from it, and the frames the physics node still holds (its
// last second, transient local) bring it up to the present: a node killed and restarted within
// half a second goes on exactly as if it had not been.

#include <string>

#include "dds/dds_participant.hpp"
#include "systems/systems_session.hpp"

namespace vcockpit::systems_node {

struct NodeOptions {
  std::string node_name = "systems_node";
  systems::SessionOptions session;
  std::string checkpoint_path;     // empty: none
  double checkpoint_every_s = 0.5;  // of simulated time
  bool resume = false;
  double duration_s = 0.0;          // stop by itself after this much real time (0: on a signal)
};

// Runs until a shutdown signal (or duration_s); returns the exit code. Throws ModelError when the
// model does not bind to the scene's controls.
int run_node(DdsParticipant& participant, systems::SystemsModel model, const NodeOptions& options);

}  // namespace vcockpit::systems_node
