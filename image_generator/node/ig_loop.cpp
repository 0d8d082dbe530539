#include "image_generator/node/ig_loop.hpp"

#include "image_generator/node/instrument_values.hpp"
#include "image_generator/node/instruments_yaml.hpp"

#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include "common/clock.hpp"
#include "common/json_file.hpp"
#include "idl/topics/pose_convert.hpp"
#include "common/latency_histogram.hpp"
#include "common/signals.hpp"
#include "image_generator/node/preview_publisher.hpp"
#include "image_generator/node/scene_cache.hpp"
#include "image_generator/node/video_recorder.hpp"

namespace vcockpit::image_generator {
namespace {

// `path`, or the first of path-2.mp4, path-3.mp4, ... that is free (neither it nor its
// .partial exists): a restarted image generator keeps the video its first run wrote, or is
// still writing (a killed one's ffmpeg finishes its file).
std::string free_video_path(const std::string& path) {
  const auto taken = [](const std::filesystem::path& p) {
    return std::filesystem::exists(p) || std::filesystem::exists(p.string() + ".partial");
  };
  if (!taken(path)) return path;
  const std::filesystem::path p(path);
  for (int n = 2;; ++n) {
    const std::filesystem::path candidate =
        p.parent_path() / (p.stem().string() + "-" + std::to_string(n) + p.extension().string());
    if (!taken(candidate)) return candidate.string();
  }
}

class ImageGenerator {
 public:
  ImageGenerator(DdsParticipant& participant, const HmdSetup& hmd, const IgOptions& options)
      : options_(options),
        X_GHead_(hmd.X_GHead),
        info_reader_(participant.make_reader<cockpit::ObjectInfo>("state")),
        hand_info_reader_(participant.make_reader<cockpit::HandInfo>("state")),
        state_reader_(participant.make_reader<cockpit::ObjectState>("state")),
        hand_reader_(participant.make_reader<cockpit::HandState>("stream")),
        head_reader_(participant.make_reader<cockpit::HeadPose>("stream")),
        control_info_reader_(participant.make_reader<cockpit::ControlInfo>("state")),
        control_reader_(participant.make_reader<cockpit::ControlState>("state")),
        frame_writer_(participant.make_writer<cockpit::FrameInfo>("stream")),
        status_writer_(participant.make_writer<cockpit::NodeStatus>("state")),
        domain_id_(participant.domain_id()),
        hmd_(hmd.hmd),
        participant_(participant) {
    if (!options.instruments_path.empty()) {
      instruments_ = load_instruments(options.instruments_path);
      render::append_instrument_faces(*instruments_, instrument_faces_);  // once: they never change
      instrument_values_.emplace(*instruments_);
      systems_info_reader_.emplace(participant.make_reader<cockpit::SystemsInfo>("state"));
      systems_state_reader_.emplace(participant.make_reader<cockpit::SystemsState>("state"));
      spdlog::info("{}: {} gauges, {} heading displays, {} lamps", options.instruments_path,
                   instruments_->gauges.size(), instruments_->headings.size(),
                   instruments_->lamps.size());
    }
    cache_.set_ghost_threshold_m(options.ghost_threshold_m);
    cache_.set_show_tracked_joints(options.show_tracked_joints);
    if (options.show_tracked_joints)
      joints_reader_.emplace(participant.make_reader<cockpit::TrackedJoints>("stream"));
  }

  int run();

 private:
  uint64_t models_refused_logged_ = 0;
  uint64_t textures_left_out_logged_ = 0;
  // A model file that failed here (the object is drawn as its box), once each; textures it names
  // that were left out; the triangles and textures loaded so far.
  void log_models() {
    if (cache_.models_refused() > models_refused_logged_) {
      models_refused_logged_ = cache_.models_refused();
      spdlog::warn("object '{}': {}; drawn as its box", info_.name().to_string(), cache_.last_model_error());
      return;
    }
    if (cache_.textures_left_out() > textures_left_out_logged_) {
      spdlog::warn("object '{}': {} texture(s) left out, drawn without (last: {})",
                   info_.name().to_string(), cache_.textures_left_out() - textures_left_out_logged_,
                   cache_.last_texture_left_out());
      textures_left_out_logged_ = cache_.textures_left_out();
    }
    spdlog::info("object '{}': model {} ({} triangles, {} textures of models in all)",
                 info_.name().to_string(), info_.mesh_file().to_string(), cache_.model_triangles(),
                 cache_.model_textures());
  }

  void drain() {
    infos_.clear();
    while (info_reader_.take(info_)) infos_.push_back(info_);
    if (!infos_.empty()) {
      // the batch's models read beforehand, each file once (a cockpit's parts are often the
      // nodes of one file)
      const model::ModelPrefetch models(cache_.model_requests(infos_));
      for (const cockpit::ObjectInfo& info : infos_) {
        info_ = info;
        cache_.on_info(info_);
        if (info_.shape() == cockpit::MESH) log_models();
      }
    }
    while (state_reader_.take(state_)) cache_.on_state(state_);
    while (hand_info_reader_.take(hand_info_)) on_hand_info();
    while (hand_reader_.take(hand_)) cache_.on_hand(hand_);
    if (joints_reader_)
      while (joints_reader_->take(joints_)) cache_.on_tracked_joints(joints_);
    while (head_reader_.take(head_)) X_GHead_ = to_eigen(head_.X_GHead());
    while (control_info_reader_.take(control_info_)) cache_.on_control_info(control_info_);
    while (control_reader_.take(control_)) cache_.on_control_state(control_);
    if (instrument_values_) {
      while (systems_info_reader_->take(systems_info_)) {
        instrument_values_->on_info(systems_info_);
        for (const std::string& name : instrument_values_->unknown())
          spdlog::warn("{}: the systems node has no system '{}': its instrument rests",
                       options_.instruments_path, name);
      }
      while (systems_state_reader_->take(systems_state_)) instrument_values_->on_state(systems_state_);
    }
  }
  void on_hand_info();
  bool wait_for_scene();
  void note_snapshot();
  void publish_status(int64_t now_ns);
  void log_frame(int64_t end_ns, int64_t display_ns);
  bool start_video();
  void finish_video();

  IgOptions options_;
  Eigen::Isometry3d X_GHead_;
  SceneCache cache_;
  Reader<cockpit::ObjectInfo> info_reader_;
  Reader<cockpit::HandInfo> hand_info_reader_;
  Reader<cockpit::ObjectState> state_reader_;
  Reader<cockpit::HandState> hand_reader_;
  std::optional<Reader<cockpit::TrackedJoints>> joints_reader_;  // with show_tracked_joints
  std::optional<render::InstrumentsSpec> instruments_;             // with instruments_path
  std::optional<InstrumentValues> instrument_values_;
  std::vector<render::Instance> instrument_faces_;  // the instruments' static layer
  std::optional<Reader<cockpit::SystemsInfo>> systems_info_reader_;
  std::optional<Reader<cockpit::SystemsState>> systems_state_reader_;
  cockpit::SystemsInfo systems_info_;
  cockpit::SystemsState systems_state_;
  Reader<cockpit::HeadPose> head_reader_;
  Reader<cockpit::ControlInfo> control_info_reader_;
  Reader<cockpit::ControlState> control_reader_;
  Writer<cockpit::FrameInfo> frame_writer_;
  Writer<cockpit::NodeStatus> status_writer_;
  int domain_id_;
  render::HmdConfig hmd_;
  DdsParticipant& participant_;
  std::unique_ptr<VideoRecorder> video_;
  std::string video_path_;
  double video_fps_ = 0.0;
  std::unique_ptr<PreviewPublisher> preview_;
  cockpit::ObjectInfo info_;
  std::vector<cockpit::ObjectInfo> infos_;  // a drain's batch
  cockpit::HandInfo hand_info_;
  cockpit::ObjectState state_;
  cockpit::HandState hand_;
  cockpit::TrackedJoints joints_;
  cockpit::HeadPose head_;
  cockpit::ControlInfo control_info_;
  cockpit::ControlState control_;
  cockpit::FrameInfo frame_;
  std::vector<render::Instance> instances_;  // the moving layer
  std::vector<render::Instance> fixed_;      // the background layer
  int64_t expected_tail_ns_ = 0;             // latch -> frame end, smoothed
  uint64_t late_frames_ = 0;                 // ended after their display slot
  uint64_t missed_slots_ = 0;                // display slots no frame ended in
  uint64_t background_redraws_ = 0;
  uint64_t last_fixed_triangles_ = 0;
  uint64_t last_moving_triangles_ = 0;
  LatencyHistogram background_ns_;  // per frame: background copied (or redrawn)
  LatencyHistogram latch_ns_;       // taking the newest state and building the moving layer
  LatencyHistogram moving_ns_;      // submitting the moving layer
  LatencyHistogram finish_ns_;      // the flush: rasterising
  std::FILE* frame_log_ = nullptr;
  uint64_t frames_ = 0;
  uint64_t frames_at_last_status_ = 0;
  int64_t render_ns_in_period_ = 0;
  int64_t last_status_ns_ = 0;
  bool warned_hand_without_info_ = false;
  std::unique_ptr<SnapshotWriter> snapshots_;
  std::FILE* snapshot_index_ = nullptr;
  // for --stats-out: every frame's render time
  LatencyHistogram render_ns_;
  int64_t first_frame_start_ns_ = 0;
  int64_t last_frame_end_ns_ = 0;

  void write_stats() const;
};

// Frames per second over the run (first render start to last render end) and render-time
// percentiles: what the benchmark reads.
void ImageGenerator::write_stats() const {
  if (options_.stats_out.empty()) return;
  // divided, not multiplied by 1e-6: a whole number of ns prints as its exact decimal
  const auto ms = [](int64_t ns) { return static_cast<double>(ns) / 1e6; };
  const double wall_s = static_cast<double>(last_frame_end_ns_ - first_frame_start_ns_) / 1e9;
  nlohmann::ordered_json j;
  j["frames"] = frames_;
  j["width_px"] = hmd_.width_px;
  j["height_px"] = hmd_.height_px;
  j["paced_fps"] = options_.fps;
  j["wall_s"] = wall_s;
  j["fps"] = wall_s > 0 ? static_cast<double>(frames_) / wall_s : 0.0;
  j["render_ms"] = {{"p50", ms(render_ns_.percentile_ns(0.5))},
                    {"p99", ms(render_ns_.percentile_ns(0.99))},
                    {"max", ms(render_ns_.max_ns())}};
  const auto part = [&](const LatencyHistogram& h) {
    return nlohmann::ordered_json{{"p50", ms(h.percentile_ns(0.5))},
                                  {"p99", ms(h.percentile_ns(0.99))}};
  };
  j["frame_parts_ms"] = {{"background", part(background_ns_)},
                         {"latch", part(latch_ns_)},
                         {"moving", part(moving_ns_)},
                         {"finish", part(finish_ns_)}};
  j["background_cache"] = options_.background_cache;
  j["background_redraws"] = background_redraws_;
  // the last frame's scene, per eye: the fixed layer's (the cockpit; drawn only when the
  // background is redrawn, else restored from the cache) and the moving layer's
  j["triangles_per_eye"] = {{"fixed", last_fixed_triangles_},
                            {"moving", last_moving_triangles_},
                            {"total", last_fixed_triangles_ + last_moving_triangles_}};
  j["predict_hand"] = options_.predict_hand;
  j["late_frames"] = late_frames_;
  j["missed_slots"] = missed_slots_;
  if (video_) {
    j["video"] = {{"path", video_path_},
                  {"ok", video_->finish()},
                  {"error", video_->error()},
                  {"width_px", video_->width_px()},
                  {"height_px", video_->height_px()},
                  {"fps", video_fps_},
                  {"frames_submitted", video_->submitted()},
                  {"frames_dropped", video_->dropped()},
                  {"video_frames", video_->video_frames()},
                  {"repeated", video_->repeated()},
                  {"skipped", video_->skipped()}};
  }
  write_json_file(options_.stats_out, j);
}

// --frame-log: each drawn hand's stamps and its tracked index fingertip as received and as
// predicted for the frame's end (bench/fingertip_error compares them with the glove log).
void ImageGenerator::log_frame(int64_t end_ns, int64_t display_ns) {
  for (uint32_t id = 0; id < SceneCache::kHandSlots; ++id) {
    Eigen::Vector3d tip, predicted;
    if (!cache_.tracked_index_tip(id, 0, tip) || !cache_.tracked_index_tip(id, display_ns, predicted))
      continue;
    const cockpit::HandState& hand = cache_.hand_state(id);
    std::fprintf(frame_log_, "%llu,%lld,%u,%lld,%lld,%lld,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f\n",
                 static_cast<unsigned long long>(frames_), static_cast<long long>(end_ns), id,
                 static_cast<long long>(hand.sample_time_ns()),
                 static_cast<long long>(hand.source_stamp_ns()),
                 static_cast<long long>(cache_.prediction_horizon_ns(id, display_ns)), tip.x(),
                 tip.y(), tip.z(), predicted.x(), predicted.y(), predicted.z());
  }
}

// snapshots.csv: which world state each snapshot shows (the held object and where it was).
void ImageGenerator::note_snapshot() {
  if (!snapshot_index_) return;
  const int held = cache_.has_hand() ? cache_.hand().grasped_object_id() : cockpit::kNoObject;
  Eigen::Vector3d p_held = Eigen::Vector3d::Zero();
  if (held != cockpit::kNoObject) p_held = cache_.object_position(static_cast<uint32_t>(held));
  Eigen::Vector3d p_palm = Eigen::Vector3d::Zero();
  if (cache_.has_hand()) p_palm = to_eigen(cache_.hand().X_GL()[0]).translation();
  std::fprintf(snapshot_index_, "%llu,%lld,%d,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f\n",
               static_cast<unsigned long long>(frames_),
               static_cast<long long>(cache_.newest_sim_time_ns()), held, p_held.x(), p_held.y(),
               p_held.z(), p_palm.x(), p_palm.y(), p_palm.z());
  std::fflush(snapshot_index_);
}

// A hand's geometry (at start, or again from a restarted physics node): its hand is drawn from now.
void ImageGenerator::on_hand_info() {
  const uint32_t id = hand_info_.hand_id();
  if (!cache_.on_hand_info(hand_info_)) {
    spdlog::warn("{} for hand {} refused (hand id beyond 1, or sizes negative or not finite)",
                 TopicTraits<cockpit::HandInfo>::kName, id);
    return;
  }
  const auto& index = hand_info_.capsules()[cockpit::INDEX_PROXIMAL];
  spdlog::info("hand {} ({}) from {}: palm {:.3f} x {:.3f} x {:.3f} m, index proximal radius "
               "{:.4f} m",
               id, hand_info_.left() ? "left" : "right", TopicTraits<cockpit::HandInfo>::kName,
               hand_info_.palm_size_m().x(), hand_info_.palm_size_m().y(),
               hand_info_.palm_size_m().z(), index.radius_m());
}

bool ImageGenerator::wait_for_scene() {
  const int64_t deadline = monotonic_now_ns() + seconds_to_ns(options_.wait_timeout_s);
  while (!shutdown_requested() && monotonic_now_ns() < deadline) {
    info_reader_.wait_for_data(50'000'000);
    drain();
    if (!cache_.has_objects()) continue;
    // the rest of the scene follows within a few ms: take it before the first frame
    std::size_t count = 0;
    while (count != cache_.object_count() && !shutdown_requested()) {
      count = cache_.object_count();
      info_reader_.wait_for_data(100'000'000);
      drain();
    }
    return true;
  }
  return false;
}

// The run's video at the paced frame rate (60 when unpaced); false if it cannot be recorded.
bool ImageGenerator::start_video() {
  if (options_.video_path.empty()) return true;
  VideoOptions video;
  video.path = free_video_path(options_.video_path);
  video.fps = options_.fps > 0 ? options_.fps : 60.0;
  video.view = options_.video_side_by_side ? VideoView::kSideBySide : VideoView::kLeftEye;
  video.scale_down = options_.video_scale_down;
  try {
    const std::filesystem::path dir = std::filesystem::path(video.path).parent_path();
    if (!dir.empty()) std::filesystem::create_directories(dir);
    video_ = std::make_unique<VideoRecorder>(video, hmd_.width_px, hmd_.height_px);
  } catch (const std::exception& e) {
    spdlog::error("video: {}", e.what());
    return false;
  }
  video_path_ = video.path;
  video_fps_ = video.fps;
  spdlog::info("video {}: {}x{} at {} frames a second ({})", video_path_, video_->width_px(),
               video_->height_px(), video.fps,
               options_.video_side_by_side ? "both eyes side by side" : "left eye");
  return true;
}

void ImageGenerator::finish_video() {
  if (!video_) return;
  if (video_->finish()) {
    spdlog::info("video {}: {} frames over {:.1f} s ({} display periods hold the previous image, "
                 "{} frames skipped over the rate), {} of {} rendered frames dropped because the "
                 "encoder was behind",
                 video_path_, video_->video_frames(),
                 static_cast<double>(video_->video_frames() + video_->repeated()) / video_fps_,
                 video_->repeated(),
                 video_->skipped(), video_->dropped(), video_->submitted());
  } else {
    spdlog::error("video {} not written: {}", video_path_, video_->error());
  }
}

void ImageGenerator::publish_status(int64_t now_ns) {
  if (now_ns - last_status_ns_ < 1'000'000'000) return;
  const double period_s = ns_to_seconds(now_ns - last_status_ns_);
  const uint64_t frames = frames_ - frames_at_last_status_;
  cockpit::NodeStatus status;
  status.node_name(options_.node_name);
  status.state(cockpit::RUNNING);
  status.stamp_ns(now_ns);
  status.loop_rate_hz(static_cast<double>(frames) / period_s);
  status.published(frames_);
  status.received(cache_.object_count());
  status.input_alive(cache_.has_hand() && cache_.hand().tracking());
  status.stage_time_us()[cockpit::STAGE_TOTAL] =
      frames > 0 ? static_cast<double>(render_ns_in_period_) * 1e-3 / static_cast<double>(frames) : 0.0;
  char detail[128];
  std::snprintf(detail, sizeof detail,
                "%d objects, snapshots %llu written %llu skipped, video frames dropped %llu, hand "
                "states without hand_info %llu",
                static_cast<int>(cache_.object_count()),
                static_cast<unsigned long long>(snapshots_ ? snapshots_->written() : 0),
                static_cast<unsigned long long>(snapshots_ ? snapshots_->skipped() : 0),
                static_cast<unsigned long long>(video_ ? video_->dropped() : 0),
                static_cast<unsigned long long>(cache_.hand_states_without_info()));
  status.detail(detail);
  status_writer_.write(status);
  if (const int id = cache_.hand_without_info(); id >= 0 && !warned_hand_without_info_) {
    spdlog::warn("hand {} on {} but no {} for it: not drawn (is the physics node an older one?)",
                 id, TopicTraits<cockpit::HandState>::kName, TopicTraits<cockpit::HandInfo>::kName);
    warned_hand_without_info_ = true;
  }
  frames_at_last_status_ = frames_;
  render_ns_in_period_ = 0;
  last_status_ns_ = now_ns;
}

int ImageGenerator::run() {
  const int64_t run_start_ns = monotonic_now_ns();
  spdlog::info("waiting for the scene on {} (domain {})",
               TopicTraits<cockpit::ObjectInfo>::kName, domain_id_);
  if (!wait_for_scene()) {
    if (shutdown_requested()) return 0;
    spdlog::error("no {} on domain {} within {} s: is physics_node running on this domain?",
                  TopicTraits<cockpit::ObjectInfo>::kName, domain_id_, options_.wait_timeout_s);
    return 3;
  }
  std::unique_ptr<render::StereoRenderer> renderer;
  try {
    renderer = std::make_unique<render::StereoRenderer>(hmd_);
  } catch (const std::exception& e) {
    spdlog::error("rendering: {}", e.what());
    return 4;
  }
  spdlog::info("{} objects; rendering {}x{} per eye with {}", cache_.object_count(),
               hmd_.width_px, hmd_.height_px, renderer->gl_renderer());
  if (!options_.out_dir.empty() && options_.snapshot_every > 0) {
    std::filesystem::create_directories(options_.out_dir);
    snapshots_ = std::make_unique<SnapshotWriter>(options_.out_dir, options_.layout,
                                                  hmd_.width_px, hmd_.height_px);
    snapshot_index_ = std::fopen((options_.out_dir + "/snapshots.csv").c_str(), "w");
    if (snapshot_index_) {
      std::fprintf(snapshot_index_,
                   "frame,sim_time_ns,held_object,held_x,held_y,held_z,palm_x,palm_y,palm_z\n");
    }
  }
  if (!start_video()) return 4;
  if (options_.preview_hz > 0) {
    preview_ = std::make_unique<PreviewPublisher>(participant_, hmd_.width_px, hmd_.height_px,
                                                  options_.preview_hz);
  }
  renderer->set_background_cache(options_.background_cache);
  if (!options_.frame_log.empty()) {
    frame_log_ = std::fopen(options_.frame_log.c_str(), "w");
    if (!frame_log_) {
      spdlog::error("--frame-log: cannot write {}", options_.frame_log);
      return 4;
    }
    std::fprintf(frame_log_, "frame,render_end_ns,hand_id,sample_time_ns,source_stamp_ns,"
                             "horizon_ns,tip_x,tip_y,tip_z,predicted_x,predicted_y,predicted_z\n");
  }
  spdlog::info("frames paced at {} Hz{}; static cockpit {}; hands {}", options_.fps,
               options_.fps > 0 ? "" : " (unpaced)",
               options_.background_cache ? "cached" : "drawn every frame",
               options_.predict_hand ? "predicted to each frame's end" : "as last received");
  // Display slots of period_ns from the first frame: a frame starts at its slot and should end
  // within it; one that ends later is counted late, and the next starts at the next free slot
  // (never two back to back to catch up).
  const int64_t period_ns = options_.fps > 0 ? std::llround(1e9 / options_.fps) : 0;
  int64_t slot_ns = monotonic_now_ns();
  last_status_ns_ = slot_ns;
  while (!shutdown_requested() && (options_.frames == 0 || frames_ < options_.frames)) {
    if (period_ns > 0) sleep_until_ns(slot_ns);
    const int64_t start_ns = monotonic_now_ns();
    // the background first (the static cockpit and the head: copied, or redrawn if they changed)
    drain();
    cache_.build_fixed(fixed_);
    fixed_.insert(fixed_.end(), instrument_faces_.begin(), instrument_faces_.end());
    renderer->begin_frame(fixed_, X_GHead_);
    // then, as late as possible, the newest hands and objects: latched here, rasterised at the
    // end_frame() flush a few ms later
    drain();
    const int64_t latch_ns = monotonic_now_ns();
    const int64_t display_ns = latch_ns + expected_tail_ns_;  // when this frame will be done
    cache_.build_moving(instances_, options_.predict_hand ? display_ns : 0);
    if (instruments_)
      render::append_instrument_indications(*instruments_, instrument_values_->values(), instances_);
    renderer->draw_moving(instances_);
    renderer->end_frame();
    const int64_t end_ns = monotonic_now_ns();
    const auto& cost = renderer->last_cost();
    // what the frame takes after the latch, smoothed: the prediction's horizon
    const int64_t tail_ns = end_ns - latch_ns;
    expected_tail_ns_ = expected_tail_ns_ == 0 ? tail_ns : (7 * expected_tail_ns_ + tail_ns) / 8;
    background_ns_.record_ns(cost.background_ns);
    latch_ns_.record_ns(latch_ns - start_ns - cost.background_ns);
    moving_ns_.record_ns(cost.moving_ns);
    finish_ns_.record_ns(cost.finish_ns);
    if (cost.background_redrawn) ++background_redraws_;
    last_fixed_triangles_ = cost.fixed_triangles;
    last_moving_triangles_ = cost.moving_triangles;
    if (period_ns > 0) {
      slot_ns += period_ns;
      if (end_ns > slot_ns) {  // missed its display slot
        ++late_frames_;
        const int64_t missed = (end_ns - slot_ns) / period_ns + 1;
        missed_slots_ += static_cast<uint64_t>(missed);
        slot_ns += missed * period_ns;
      }
    }
    if (frame_log_) log_frame(end_ns, display_ns);
    render_ns_in_period_ += end_ns - start_ns;
    if (frames_ == 0) {
      first_frame_start_ns_ = start_ns;
      // how long a (re)started image generator leaves the display dark
      spdlog::info("first frame rendered {:.2f} s after start ({:.2f} s of it this frame)",
                   ns_to_seconds(end_ns - run_start_ns), ns_to_seconds(end_ns - start_ns));
    }
    last_frame_end_ns_ = end_ns;
    render_ns_.record_ns(end_ns - start_ns);
    frame_.frame_seq(frames_);
    frame_.width_px(static_cast<uint32_t>(hmd_.width_px));
    frame_.height_px(static_cast<uint32_t>(hmd_.height_px));
    frame_.sim_time_ns(cache_.newest_sim_time_ns());
    frame_.sample_time_ns(cache_.has_hand() ? cache_.hand().sample_time_ns() : 0);
    frame_.source_stamp_ns(cache_.has_hand() ? cache_.hand().source_stamp_ns() : 0);
    frame_.render_start_ns(latch_ns);  // the hand data drawn was taken here
    frame_.render_end_ns(end_ns);
    frame_writer_.write(frame_);
    if (video_) video_->submit(renderer->shared_pixels(), end_ns, cache_.newest_sim_time_ns());
    if (preview_) preview_->offer(renderer->pixels(), frames_, cache_.newest_sim_time_ns(), end_ns);
    if (snapshots_ && frames_ % static_cast<uint64_t>(options_.snapshot_every) == 0 &&
        snapshots_->submit(frames_, renderer->pixels())) {
      note_snapshot();
    }
    ++frames_;
    publish_status(end_ns);
  }
  const uint64_t written = snapshots_ ? snapshots_->written() : 0;
  snapshots_.reset();  // finishes the queued PNGs
  if (frame_log_) std::fclose(frame_log_);
  spdlog::info("frames: {} late (after their display slot), {} display slots missed; background "
               "redrawn {} times; per frame p50: background {:.2f} ms, latch {:.2f} ms, moving "
               "{:.2f} ms, finish {:.2f} ms",
               late_frames_, missed_slots_, background_redraws_,
               static_cast<double>(background_ns_.percentile_ns(0.5)) * 1e-6,
               static_cast<double>(latch_ns_.percentile_ns(0.5)) * 1e-6,
               static_cast<double>(moving_ns_.percentile_ns(0.5)) * 1e-6,
               static_cast<double>(finish_ns_.percentile_ns(0.5)) * 1e-6);
  preview_.reset();
  finish_video();
  if (snapshot_index_) std::fclose(snapshot_index_);
  spdlog::info("rendered {} frames; snapshots written {}", frames_, written);
  if (cache_.hand_messages_refused() > 0) {
    spdlog::warn("{} hand_state/hand_info messages refused", cache_.hand_messages_refused());
  }
  write_stats();
  return 0;
}

}  // namespace

int run_image_generator(DdsParticipant& participant, const HmdSetup& hmd,
                        const IgOptions& options) {
  ImageGenerator ig(participant, hmd, options);
  return ig.run();
}

}  // namespace vcockpit::image_generator
