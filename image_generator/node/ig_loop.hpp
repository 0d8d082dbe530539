#pragma once
// image_generator over DDS: the scene from cockpit/object_info + object_state + hand_info +
// hand_state (a late starter gets it from the transient-local topics; the hand's geometry comes
// from the physics node's hand_info, no hand.yaml here), the head from cockpit/head_pose or the
// design eye point, stereo frames rendered off-screen, cockpit/frame_info for every frame, PNG
// snapshots every N frames, the run's video, pictures for instructor displays
// (cockpit/preview_frame), node_status once a second.

#include <cstdint>
#include <string>

#include "dds/dds_participant.hpp"
#include "image_generator/node/hmd_yaml.hpp"
#include "image_generator/node/snapshot_writer.hpp"

#include "image_generator/node/scene_cache.hpp"

namespace vcockpit::image_generator {

struct IgOptions {
  std::string out_dir;           // snapshots; empty: none
  int snapshot_every = 30;       // frames between snapshots; 0: none
  SnapshotLayout layout = SnapshotLayout::kSideBySide;
  uint64_t frames = 0;           // render this many and exit; 0: until a signal
  double fps = 90.0;             // frame pacing (the display's refresh); 0: as fast as possible
  double wait_timeout_s = 10.0;  // for the first object_info
  std::string node_name = "image_generator";
  std::string stats_out;         // JSON file of the run's frame rate and render times; empty: none
  double ghost_threshold_m = SceneCache::kDefaultGhostThreshold_m;  // tracked-hand ghost
  bool show_tracked_joints = false;  // cockpit/tracked_joints as dots beside each hand
  // The run's video (video_recorder.hpp): OUT/rig.mp4 say; empty: none. An existing file is not
  // overwritten (a restarted image generator writes rig-2.mp4 beside it).
  std::string video_path;
  int video_scale_down = 2;      // 1280x720 eyes as a 640x360 video
  bool video_side_by_side = false;
  double preview_hz = 4.0;       // cockpit/preview_frame pictures a second; 0: none
  bool background_cache = true;  // the static cockpit drawn once (stereo_renderer.hpp)
  bool predict_hand = false;     // hands extrapolated to the frame's end (hand_prediction.hpp)
  std::string frame_log;         // per frame and hand: stamps and index fingertips (CSV); "": none
  std::string instruments_path;  // the panel's live instruments (config/instruments.yaml); "": none
};

// Exit codes: 0 done, 3 no scene arrived in time, 4 rendering failed.
int run_image_generator(DdsParticipant& participant, const HmdSetup& hmd,
                        const IgOptions& options);

}  // namespace vcockpit::image_generator
