#include "physics_node/node/world_stepper.hpp"

#include <spdlog/spdlog.h>

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>

#include "common/clock.hpp"
#include "physics_node/io/grasp_event_text.hpp"

namespace vcockpit::physics_node {

WorldStepper::WorldStepper(DdsParticipant& participant, physics::World& world,
                           StatePublisher& publisher, SimCommands& sim, const NodeOptions& options)
    : options_(options),
      world_(world),
      publisher_(publisher),
      sim_(sim),
      // volatile: a node (re)started later does not carry out old commands
      command_reader_(participant.make_reader<cockpit::ControlCommand>("command")),
      frames_(participant, world.scene(), options.control_frame_hz) {
  if (!options.checkpoint_path.empty()) {
    const std::filesystem::path dir = std::filesystem::path(options.checkpoint_path).parent_path();
    std::error_code error;
    if (!dir.empty()) std::filesystem::create_directories(dir, error);
    if (error)
      throw std::runtime_error("--checkpoint: cannot create " + dir.string() + ": " + error.message());
    // the fingerprint of the scene as it starts, then (--resume) the newest save
    fingerprint_ = physics_io::scene_fingerprint(world_);
    if (options.resume) resume_from_checkpoint();
    checkpointer_ = std::make_unique<CheckpointWriter>(options.checkpoint_path, fingerprint_);
    next_checkpoint_ns_ = world_.time_ns() + seconds_to_ns(options.checkpoint_every_s);
  }
  if (!options.out_dir.empty()) {
    recorder_ = std::make_unique<physics_io::RunRecorder>(
        options.out_dir, physics_io::output_interval_ns(options.output_hz, world_.scene()),
        physics_io::control_frame_interval_ns(
            options.control_frame_hz > 0 ? options.control_frame_hz : 100.0, world_.scene()),
        world_.scene());
  }
}

void WorldStepper::step(LoopStats& stats) {
  take_commands();
  const int64_t start_ns = monotonic_now_ns();
  world_.step();
  stats.step_compute.record_ns(monotonic_now_ns() - start_ns);
  hand_peak_.record(world_);
  if (recorder_) recorder_->after_step(world_);
  publish_events();
  frames_.after_step(world_);
  ++steps_in_period_;
  for (int s = 0; s < physics::kStageCount; ++s) stage_ns_[s] += world_.stage_times().ns[s];
  maybe_checkpoint();
}

void WorldStepper::clear_period() {
  steps_in_period_ = 0;
  stage_ns_.fill(0);
}

void WorldStepper::take_commands() {
  while (command_reader_.take(command_)) {
    const auto& controls = world_.scene().controls;
    const int control = static_cast<int>(command_.control_id());
    const int position = static_cast<int>(command_.position());
    if (world_.command_control(control, position)) {
      spdlog::info("command from '{}': {} to {}", command_.source(), controls[control].name,
                   controls[control].positions[static_cast<std::size_t>(position)].name);
    } else {
      ++commands_refused_;
      spdlog::warn("command from '{}' refused: control {} position {} ({})", command_.source(),
                   command_.control_id(), command_.position(),
                   control >= 0 && control < static_cast<int>(controls.size())
                       ? "no such position, or a hand holds it"
                       : "no such control");
    }
  }
}

void WorldStepper::resume_from_checkpoint() {
  const std::string& path = options_.checkpoint_path;
  std::optional<physics_io::Checkpoint> saved;
  try {
    saved = physics_io::read_checkpoint_file(path, world_);
  } catch (const physics_io::CheckpointError& e) {
    std::error_code ignored;
    std::filesystem::rename(path, path + ".bad", ignored);
    spdlog::error("not resumed: {} (kept as {}.bad); starting from the scene", e.what(), path);
    return;
  }
  if (!saved) {
    spdlog::warn("not resumed: no checkpoint {} yet; starting from the scene", path);
    return;
  }
  world_.restore(saved->world);
  sim_.restore_frozen(saved->frozen);
  int held = 0;
  for (const physics::BodyState& b : world_.state().bodies) held += b.held() ? 1 : 0;
  spdlog::info("resumed from {}: {:.3f} s simulated, {} steps, {} object(s) held{}; the hands "
               "take up their gloves from their next samples",
               path, ns_to_seconds(world_.time_ns()), world_.step_count(), held,
               saved->frozen ? ", frozen" : "");
}

void WorldStepper::maybe_checkpoint(bool force) {
  if (!checkpointer_ || (!force && world_.time_ns() < next_checkpoint_ns_)) return;
  checkpoint_.world = world_.state();  // into the buffers of an older one: no allocation
  checkpoint_.frozen = sim_.frozen();
  checkpointer_->offer(checkpoint_);
  next_checkpoint_ns_ = world_.time_ns() + seconds_to_ns(options_.checkpoint_every_s);
}

void WorldStepper::finish_checkpoints() {
  if (!checkpointer_) return;
  maybe_checkpoint(true);
  checkpointer_->flush();
  spdlog::info("checkpoints: {} written to {}, {} replaced by a newer one before written, {} "
               "failed",
               checkpointer_->written(), checkpointer_->path(), checkpointer_->superseded(),
               checkpointer_->failed());
}

void WorldStepper::start_recording_once() {
  if (!recorder_ || recording_started_) return;
  recorder_->start(world_);
  recording_started_ = true;
}

void WorldStepper::commit_recording() {
  if (!recorder_) return;
  start_recording_once();
  recorder_->commit();
  spdlog::info("wrote {}/trajectories.csv and events.jsonl", options_.out_dir);
}

void WorldStepper::publish_events() {
  publisher_.publish_events(world_);
  log_events();
}

void WorldStepper::log_events() {
  for (const auto& f : world_.step_faults()) {
    spdlog::warn("object '{}' (#{}): {} at {:.3f} s, put back where it was at the step's start, "
                 "at rest (further faults of it are counted, not logged)",
                 world_.scene().objects[f.object].name, f.object,
                 physics::body_fault_name(f.what), ns_to_seconds(f.first_t_ns));
  }
  for (const auto& e : world_.step_events()) {
    const int h = world_.hand_index(e.hand_id);
    if (e.grasp && h >= 0) ++grasps_[static_cast<std::size_t>(h)];
    spdlog::info("{} {} at {:.3f} s{}: {}", e.grasp ? "GRASP" : "RELEASE",
                 world_.scene().objects[e.object].name, ns_to_seconds(e.t_ns),
                 world_.hand_count() > 1
                     ? std::string(" by the ") + (e.hand_id == 1 ? "left" : "right") + " hand"
                     : std::string(),
                 physics_io::grasp_event_text(e));
  }
  for (const auto& e : world_.control_events()) {
    const physics::ControlSpec& c = world_.scene().controls[static_cast<std::size_t>(e.control)];
    spdlog::info("CONTROL {} {} -> {} at {:.3f} s: {}{}{}", c.name,
                 c.positions[static_cast<std::size_t>(e.from)].name,
                 c.positions[static_cast<std::size_t>(e.to)].name, ns_to_seconds(e.t_ns),
                 physics::control_cause_name(e.cause), e.link >= 0 ? " by " : "",
                 e.link >= 0 ? std::string(physics::link_name(static_cast<physics::Link>(e.link)))
                             : std::string());
  }
}

}  // namespace vcockpit::physics_node
