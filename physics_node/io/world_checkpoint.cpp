#include "physics_node/io/world_checkpoint.hpp"

#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <type_traits>

#include "common/atomic_file.hpp"
#include "physics_node/physics/world_state_fields.hpp"
#include "physics_node/physics/world_state_hash.hpp"

namespace vcockpit::physics_io {
namespace {

constexpr char kMagic[8] = {'V', 'C', 'K', 'P', 'O', 'I', 'N', 'T'};
// 2: GraspHold::opposed_fingers and palm_opposed; 3: GraspHold::grip_tightest_rad;
// 4: HandState::finger_pull_G; 5: BodyState's sleep (still_s, asleep, island); 6: the stick
// anchors' impulses (the soft solver's warm start); 7: GraspHold::grip_gap_m; 8: no substep
// count, no HandState::fingers_on_held (contacts are soft constraints: one solve a step);
// 9: GraspHold::passing_through
constexpr uint64_t kVersion = 9;
constexpr uint64_t kFrozenFlag = 1;
// anchors are per touching pair: far more than any scene makes, far less than a corrupt length
constexpr uint64_t kMaxVarCount = 1u << 16;

uint64_t fnv1a64(std::string_view bytes) {
  uint64_t h = 14695981039346656037ull;
  for (const char c : bytes) {
    h ^= static_cast<unsigned char>(c);
    h *= 1099511628211ull;
  }
  return h;
}

void put_u64(std::string& out, uint64_t v) {
  char bytes[8];
  for (int byte = 0; byte < 8; ++byte)
    bytes[byte] = static_cast<char>((v >> (8 * byte)) & 0xffu);
  out.append(bytes, sizeof bytes);
}

uint64_t get_u64(std::string_view bytes, std::size_t at) {
  uint64_t v = 0;
  for (int byte = 0; byte < 8; ++byte)
    v |= static_cast<uint64_t>(static_cast<unsigned char>(bytes[at + static_cast<std::size_t>(byte)]))
         << (8 * byte);
  return v;
}

// visit_world_state's visitor that appends every field.
class Writer {
 public:
  explicit Writer(std::string& out) : out_(out) {}
  template <class T>
  void num(const T& x) {
    if constexpr (std::is_floating_point_v<T>) {
      put_u64(out_, std::bit_cast<uint64_t>(static_cast<double>(x)));
    } else if constexpr (std::is_same_v<T, bool>) {
      put_u64(out_, x ? 1u : 0u);
    } else if constexpr (std::is_signed_v<T>) {
      put_u64(out_, static_cast<uint64_t>(static_cast<int64_t>(x)));
    } else {
      put_u64(out_, static_cast<uint64_t>(x));
    }
  }
  template <class Vec>
  void count(const Vec& v) { put_u64(out_, v.size()); }
  template <class Vec>
  void var_count(const Vec& v) { put_u64(out_, v.size()); }
  void fixed(std::size_t n) { put_u64(out_, n); }

 private:
  std::string& out_;
};

// visit_world_state's visitor that fills a state of the scene's shape, checking as it goes.
class Reader {
 public:
  explicit Reader(std::string_view bytes, std::size_t at) : bytes_(bytes), at_(at) {}
  std::size_t position() const { return at_; }

  template <class T>
  void num(T& x) {
    const uint64_t v = next("a number");
    if constexpr (std::is_floating_point_v<T>) {
      const double d = std::bit_cast<double>(v);
      if (!std::isfinite(d)) fail("a number that is not finite");
      x = static_cast<T>(d);
    } else if constexpr (std::is_same_v<T, bool>) {
      if (v > 1) fail("a flag that is neither 0 nor 1");
      x = v == 1;
    } else if constexpr (std::is_signed_v<T>) {
      const auto s = static_cast<int64_t>(v);
      if (s < std::numeric_limits<T>::min() || s > std::numeric_limits<T>::max())
        fail("an integer out of its range");
      x = static_cast<T>(s);
    } else {
      if (v > std::numeric_limits<T>::max()) fail("an integer out of its range");
      x = static_cast<T>(v);
    }
  }
  template <class Vec>
  void count(Vec& v) {
    const uint64_t n = next("a length");
    if (n != v.size()) {
      fail("a length of " + std::to_string(n) + " where this scene has " +
           std::to_string(v.size()) + " (a checkpoint of another scene?)");
    }
  }
  template <class Vec>
  void var_count(Vec& v) {
    const uint64_t n = next("a length");
    if (n > kMaxVarCount) fail("a length of " + std::to_string(n));
    v.resize(static_cast<std::size_t>(n));
  }
  void fixed(std::size_t n) {
    if (next("a length") != n) fail("a joint or link count that is not the hand's");
  }

  uint64_t next(const char* what) {
    if (bytes_.size() - at_ < 8) fail(std::string("the file ends where ") + what + " should be");
    const uint64_t v = get_u64(bytes_, at_);
    at_ += 8;
    return v;
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw CheckpointError(what + " at byte " + std::to_string(at_));
  }

 private:
  std::string_view bytes_;
  std::size_t at_;
};

// Indices a world would follow: a state whose numbers are all finite could still point outside
// the scene, and stepping it would read out of bounds.
void check_indices(const physics::WorldState& s, const physics::Scene& scene) {
  const int hand_count = static_cast<int>(scene.hands.size());
  const int object_count = static_cast<int>(scene.objects.size());
  auto bad = [](const std::string& what) { throw CheckpointError(what); };
  if (s.time_ns < 0) bad("a negative time");
  const uint64_t holders_limit = 1u << hand_count;
  for (std::size_t i = 0; i < s.bodies.size(); ++i) {
    const physics::BodyState& b = s.bodies[i];
    const std::string object = "object " + std::to_string(i);
    if (b.holders >= holders_limit) bad(object + " held by a hand the scene has not");
    if (b.held_by != physics::kNotHeld && (b.held_by < 0 || b.held_by > 1))
      bad(object + " held by hand id " + std::to_string(b.held_by));
    // the grasp decisions take a held body's pose ring: only dynamic objects are ever held
    if ((b.holders != 0) != (b.held_by != physics::kNotHeld))
      bad(object + " held and not held (its holders and held_by disagree)");
    if (b.holders != 0 && !scene.objects[i].dynamic) bad(object + " is static and held");
    // only a free object sleeps (sleep.hpp): a sleeping held one would never be let go
    if (b.asleep && (b.holders != 0 || !scene.objects[i].dynamic || scene.objects[i].control >= 0))
      bad(object + " asleep but not free (held, static or a control)");
    if (b.asleep && (b.island < 0 || b.island >= object_count))
      bad(object + " asleep in island " + std::to_string(b.island));
    if (!(b.still_s >= 0.0)) bad(object + " still for a negative time");
  }
  for (const physics::HandState& h : s.hands) {
    if (h.blocking_out_G.size() > static_cast<std::size_t>(physics::kMaxBlockingPlanes))
      bad("more blocking planes than a hand keeps");
    if (h.finger_pull_G.norm() > 1.001 * physics::kMaxFingerPull_m)
      bad("a finger pull farther than a hand keeps");
    for (const physics::GraspHold& g : h.grasp) {
      // (a static object's ring is empty)
      const std::size_t n = g.history.size();
      if (n == 0 ? g.history_next != 0 || g.history_count != 0
                 : g.history_next >= n || g.history_count > n)
        bad("a grasp's pose ring out of its bounds");
    }
  }
  for (std::size_t c = 0; c < s.controls.size(); ++c) {
    const physics::ControlState& cs = s.controls[c];
    if (cs.position < 0 || cs.position >= static_cast<int>(scene.controls[c].positions.size()))
      bad("control " + std::to_string(c) + " at a position it has not");
    if (cs.push_hand < -1 || cs.push_hand >= hand_count || cs.push_link < -1 ||
        cs.push_link >= static_cast<int>(physics::kLinkCount) || cs.push_direction < -1 ||
        cs.push_direction > 1)
      bad("control " + std::to_string(c) + " pushed by a link the scene has not");
  }
  const int bodies = object_count + hand_count * static_cast<int>(physics::kLinkCount);
  for (const physics::StickAnchor& a : s.anchors) {
    if (a.body_a < 0 || a.body_a >= bodies || a.body_b < 0 || a.body_b >= bodies)
      bad("a friction anchor on a body the scene has not");
  }
}

}  // namespace

uint64_t scene_fingerprint(const physics::World& fresh_world) {
  std::string text;
  const physics::Scene& scene = fresh_world.scene();
  put_u64(text, physics::hash_world_state(fresh_world.state()));
  put_u64(text, std::bit_cast<uint64_t>(scene.step_s));
  for (const auto& object : scene.objects) text += object.name + '\n';
  for (const auto& control : scene.controls) {
    text += control.name + ':';
    for (const auto& position : control.positions) text += position.name + ',';
    text += '\n';
  }
  put_u64(text, scene.hands.size());
  return fnv1a64(text);
}

std::string encode_checkpoint(const Checkpoint& checkpoint, uint64_t fingerprint) {
  std::string out;
  encode_checkpoint(checkpoint, fingerprint, out);
  return out;
}

void encode_checkpoint(const Checkpoint& checkpoint, uint64_t fingerprint, std::string& out) {
  out.assign(kMagic, sizeof kMagic);
  put_u64(out, kVersion);
  put_u64(out, fingerprint);
  put_u64(out, checkpoint.frozen ? kFrozenFlag : 0u);
  Writer writer(out);
  physics::visit_world_state(writer, checkpoint.world);
  put_u64(out, fnv1a64(out));
}

Checkpoint decode_checkpoint(std::string_view bytes, const physics::World& fresh_world) {
  constexpr std::size_t kHeader = sizeof kMagic + 3 * 8;
  if (bytes.size() < kHeader + 8) throw CheckpointError("too short to be a checkpoint");
  if (std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0)
    throw CheckpointError("not a checkpoint (no VCKPOINT at its start)");
  const uint64_t version = get_u64(bytes, 8);
  if (version != kVersion)
    throw CheckpointError("format version " + std::to_string(version) + ", this build reads " +
                          std::to_string(kVersion));
  const std::string_view body = bytes.substr(0, bytes.size() - 8);
  if (fnv1a64(body) != get_u64(bytes, bytes.size() - 8))
    throw CheckpointError("its checksum does not match (damaged)");
  if (get_u64(bytes, 16) != scene_fingerprint(fresh_world))
    throw CheckpointError("saved from another scene (objects, controls, hands or their start differ)");
  const uint64_t flags = get_u64(bytes, 24);
  if ((flags & ~kFrozenFlag) != 0) throw CheckpointError("unknown flags");
  Checkpoint checkpoint;
  checkpoint.frozen = (flags & kFrozenFlag) != 0;
  checkpoint.world = fresh_world.state();  // the scene's lengths
  Reader reader(body, kHeader);
  physics::visit_world_state(reader, checkpoint.world);
  if (reader.position() != body.size())
    throw CheckpointError(std::to_string(body.size() - reader.position()) +
                          " bytes after the world's state");
  check_indices(checkpoint.world, fresh_world.scene());
  return checkpoint;
}

void write_checkpoint_file(const std::string& path, std::string_view bytes) {
  AtomicFile file(path);
  file.write(bytes);
  file.commit();
}

std::optional<Checkpoint> read_checkpoint_file(const std::string& path,
                                               const physics::World& fresh_world) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream text;
  text << in.rdbuf();
  try {
    return decode_checkpoint(text.str(), fresh_world);
  } catch (const CheckpointError& e) {
    throw CheckpointError(path + ": " + e.what());
  }
}

}  // namespace vcockpit::physics_io
