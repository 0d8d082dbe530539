#pragma once
// LeapJS playback JSON (Leap Motion's recorder, protocol 6) into hand-joints frames.
//
// Each frame has `timestamp` (µs), `hands[]` (`id`, `type` left/right, `palmPosition` mm,
// `direction` toward the fingers, `palmNormal` out of the palm) and `pointables[]` (`handId`,
// `type` 0 thumb .. 4 little, `mcpPosition`, `pipPosition`, `dipPosition`, `tipPosition` mm,
// `width` mm), in the controller's frame: +y up, +z toward the user, the OpenXR convention, so
// the frames come out in JointsSpace::kXr, in metres, with t = timestamp - the first frame's.
// Leap models the thumb with a metacarpal of zero length: its mcp is the thumb's carpometacarpal
// joint (OpenXR thumb_metacarpal), its pip the thumb's MCP (thumb_proximal), its dip the IP
// (thumb_distal). The fingers' metacarpal bases and the wrist are not in the protocol: those
// joints are not valid. The palm's orientation comes from `direction` and `palmNormal` (the
// hand's `r` is its rotation since an earlier frame, not a basis). Radii are half the `width`.
// A frame without hands is skipped (the hand is lost until the next one); a frame whose time
// does not increase is skipped and counted. A file that is not JSON, or a frame without a
// needed field or with a non-finite number, is an error naming the file, the frame and the field.

#include <string>
#include <vector>

#include "hand/tracking/tracker_json.hpp"

namespace vcockpit::hand::tracking {

struct LeapImport : TrackerImport {
  int protocol_version = 0;  // metadata.protocolVersion (0: not given)
};

// Throws JointsLogError.
LeapImport import_leapjs(const std::string& path);

}  // namespace vcockpit::hand::tracking
