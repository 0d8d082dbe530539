#pragma once
// A world checkpoint: the WorldState (every field, world_state_fields.hpp) in a small binary file
// that a physics node writes every few seconds of simulated time and a restarted one resumes
// from (kill -9, a crash, a power cut: the file is written whole or not at all).
//
// Layout, every number 8 bytes little-endian (a double as its IEEE-754 bits):
//   "VCKPOINT" (8 bytes), format version, the scene's fingerprint, the node's flags (bit 0:
//   frozen), then the WorldState's fields in visit_world_state's order, then an FNV-1a 64 of
//   every byte before it.
// Reading checks all of it: magic, version, scene, checksum, every length against the scene's
// (objects, controls, hands, grasp windows), every index in range, every number finite; a file
// that fails any is refused with what failed, never half-restored.

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "physics_node/physics/world.hpp"

namespace vcockpit::physics_io {

class CheckpointError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Checkpoint {
  physics::WorldState world;
  bool frozen = false;  // the instructor had frozen the simulation
};

// What a checkpoint must match: the scene's objects, controls and hands, their names and starting
// state, and the step (a checkpoint of another scene is refused).
uint64_t scene_fingerprint(const physics::World& fresh_world);

std::string encode_checkpoint(const Checkpoint& checkpoint, uint64_t fingerprint);
// The same into `out` (its capacity reused).
void encode_checkpoint(const Checkpoint& checkpoint, uint64_t fingerprint, std::string& out);

// `fresh_world`: a world of this scene as it starts (its fingerprint and lengths are what a
// checkpoint must have). Throws CheckpointError saying what is wrong.
Checkpoint decode_checkpoint(std::string_view bytes, const physics::World& fresh_world);

// Writes atomically (a .partial file, fsync, rename); throws FileError naming the path.
void write_checkpoint_file(const std::string& path, std::string_view bytes);

// The checkpoint in `path`, or nothing when there is no such file. Throws CheckpointError
// naming the file and what is wrong with it.
std::optional<Checkpoint> read_checkpoint_file(const std::string& path,
                                               const physics::World& fresh_world);

}  // namespace vcockpit::physics_io
