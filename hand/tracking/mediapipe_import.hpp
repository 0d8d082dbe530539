#pragma once
// MediaPipe Hands world landmarks (JSON) into hand-joints frames.
//
// The file is a list of frames, or {"frames": [...]}. Each frame is the hand landmarker's result
// as its JavaScript API gives it (HandLandmarkerResult), with the frame's time added:
//   {"timestamp_ms": 33.4,                                     or "timestampMs", or "t_s" (s)
//    "worldLandmarks": [[{"x": .., "y": .., "z": ..}, ... 21], ...],   one list per hand
//    "handednesses": [[{"categoryName": "Right", "score": 0.97}], ...]}
// The Python API's names are taken too (hand_world_landmarks, handedness, category_name). World
// landmarks are in metres about the hand's own centre, x right, y down, z away from the camera:
// they come out in JointsSpace::kXr as (x, -y, -z). Being centred on the hand in every frame,
// they carry the hand's shape and turn but not its place in the room: the replayed hand stays
// where it is placed.
// Landmarks: 0 wrist; 1-4 thumb CMC, MCP, IP, tip (OpenXR thumb_metacarpal, _proximal,
// _distal, _tip); then per finger (index, middle, ring, little) MCP, PIP, DIP, tip (_proximal,
// _intermediate, _distal, _tip). The palm and the fingers' metacarpal bases are not tracked.
// Handedness is MediaPipe's label as it is (it assumes a mirrored, selfie-view image).
// A frame without hands is skipped; time not increasing is skipped and counted. A file that is
// not JSON, or a frame missing a field or with a non-finite number, is an error naming the file,
// the frame and the field.

#include <string>
#include <vector>

#include "hand/tracking/tracker_json.hpp"

namespace vcockpit::hand::tracking {

using MediaPipeImport = TrackerImport;

// Throws JointsLogError.
MediaPipeImport import_mediapipe(const std::string& path);

}  // namespace vcockpit::hand::tracking
