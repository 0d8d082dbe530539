#pragma once
// --record: subscribes to cockpit/hand_sample and writes a glove log. The log is written to
// "<path>.partial" and renamed into place on a clean stop (signal, --count, --duration or
// --idle-timeout), so an interrupted recording never leaves a corrupt log.
//
// It takes what its writers offer: a reliable reader (deep history, repairs requested) gets the
// samples of reliable writers, a best-effort reader those of the others; a sample both deliver
// is written once. Each writer's sequence numbers tell what never arrived: the count is logged on
// exit and written as a "# lost: ..." line at the end of the log.

#include <cstdint>
#include <string>

#include "dds/dds_participant.hpp"
#include "hand/hand_model.hpp"

namespace vcockpit::glove {

struct RecorderOptions {
  std::string path;
  bool lockstep = false;       // one reliable keep-all reader (pairs with a lockstep publisher)
  uint32_t hand_id = 0;        // records this hand's samples only
  uint64_t count = 0;          // stop after this many samples (0: no limit)
  double duration_s = 0.0;     // stop after this long (0: no limit)
  double idle_timeout_s = 0.0;  // stop this long after the last sample (0: never)
  std::string node_name = "glove_recorder";
};

// Returns the process exit code: 0 when the log was written.
int run_recorder(DdsParticipant& participant, const hand::HandModel& hand,
                 const RecorderOptions& options);

}  // namespace vcockpit::glove
