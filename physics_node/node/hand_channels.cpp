#include "physics_node/node/hand_channels.hpp"

#include <spdlog/spdlog.h>

#include <stdexcept>

#include "common/clock.hpp"

namespace vcockpit::physics_node {
namespace {

physics_io::FollowerOptions follower_options(const NodeOptions& options) {
  physics_io::FollowerOptions f;
  f.max_gap_ns = options.timing.max_gap_ns;
  if (options.input_delay_s) f.fixed_delay_ns = seconds_to_ns(*options.input_delay_s);
  return f;
}

}  // namespace

HandChannel::HandChannel(physics::World& world, int hand_index, const NodeOptions& options)
    : hand(hand_index),
      model(world.scene().hands[static_cast<std::size_t>(hand_index)]),
      gate(model),
      replay(world, model, options.timing, hand_index),
      follower(follower_options(options)) {}

HandChannels::HandChannels(DdsParticipant& participant, physics::World& world,
                           const NodeOptions& options)
    : options_(options),
      world_(world),
      reader_(participant.make_reader<cockpit::HandSample>(options.lockstep ? "reliable" : "stream")) {
  channels_.reserve(static_cast<std::size_t>(world.hand_count()));
  for (int h = 0; h < world.hand_count(); ++h) channels_.emplace_back(world, h, options);
  for (const int id : options.lockstep_hands) {
    const int h = world.hand_index(id);
    if (h < 0) throw std::invalid_argument("--lockstep-hands: the scene has no such hand");
    channels_[static_cast<std::size_t>(h)].expected = true;
  }
}

HandChannel* HandChannels::accept(const dds::SampleInfo& info) {
  const int h = world_.hand_index(static_cast<int>(message_.hand_id()));
  if (h < 0) {  // a hand this scene does not have: refused and counted
    if (unknown_hand_++ == 0)
      spdlog::warn("hand samples for hand_id {}, which the scene has not: ignored (counted)",
                   message_.hand_id());
    return nullptr;
  }
  HandChannel& ch = channels_[static_cast<std::size_t>(h)];
  new_source_ = !ch.have_source || info.publication_handle != ch.source;
  if (new_source_) ch.gate.reset_time();
  if (!ch.gate.accept(message_, sample_)) return nullptr;
  if (new_source_) {
    if (ch.have_source)
      spdlog::info("{} hand samples from a new source: following its timeline", side_name(h));
    ch.source = info.publication_handle;
    ch.have_source = true;
  }
  ++received_;
  ++ch.received;
  return &ch;
}

bool HandChannels::glove_alive(const HandChannel& ch, int64_t now_ns) const {
  if (ch.received == 0) return false;
  const bool recent = now_ns - ch.last_sample_wall_ns <= options_.timing.glove_timeout_ns;
  return recent && reader_.alive_writer_count() > 0;
}

bool HandChannels::any_alive(int64_t now_ns) const {
  for (const HandChannel& ch : channels_)
    if (glove_alive(ch, now_ns)) return true;
  return false;
}

bool HandChannels::track_gloves(int64_t now_ns) {
  bool any_alive = false;
  for (HandChannel& ch : channels_) {
    const bool alive = glove_alive(ch, now_ns);
    if (alive != ch.tracking && ch.have_input) {
      if (alive) {
        spdlog::warn("{} glove samples resumed: tracking", side_name(ch.hand));
      } else {
        spdlog::warn("{} glove lost: holding the hand, releasing what it holds", side_name(ch.hand));
        ++ch.glove_lost;
      }
    }
    ch.tracking = alive;
    any_alive = any_alive || alive;
  }
  return any_alive;
}

hand::InputCounts HandChannels::counts(const HandChannel& ch) const {
  hand::InputCounts c = ch.gate.counts();
  c.rejected_out_of_range += ch.gate.rejected_flagged_or_far();  // as node_status always had it
  c += options_.lockstep ? ch.replay.counts() : ch.follower.counts();
  c.glove_lost += ch.glove_lost;
  return c;
}

hand::InputCounts HandChannels::counts() const {
  hand::InputCounts c;
  for (const HandChannel& ch : channels_) c += counts(ch);
  return c;
}

uint64_t HandChannels::rejected() const {
  uint64_t n = unknown_hand_;
  for (const HandChannel& ch : channels_) n += ch.gate.rejected();
  return n;
}

const char* HandChannels::side_name(int hand) const {
  return world_.hand_id(hand) == 1 ? "left" : "right";
}

}  // namespace vcockpit::physics_node
