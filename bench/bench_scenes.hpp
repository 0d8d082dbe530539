#pragma once
// The scenes every physics benchmark runs (ours and MuJoCo's), built the same way each time:
//   - the default cockpit (config/cockpit.yaml with config/hand.yaml), the hand holding the cup;
//   - the same cockpit with N loose objects on the floor (a generated, seeded scene), to show how
//     the step cost grows with the number of dynamic objects.
// "Holding" comes from the bundled glove log: the world is stepped through it up to a moment the
// cup is held, and the hand is then kept there, so every timed step has the hand in contact.

#include <cstdint>
#include <string>
#include <vector>

#include "physics_node/physics/scene.hpp"
#include "physics_node/physics/world.hpp"

namespace vcockpit::bench {

// A file of the source tree (config/..., bench/...).
std::string source_path(const std::string& relative);

physics::Scene cockpit_scene();

// The cockpit plus `loose_objects` dynamic objects (boxes, spheres, capsules and cylinders of
// 3.5-7 cm, 400-900 kg/m^3) resting apart on a cargo floor behind the back wall (the floor extended
// back to x = -2.2 m; at most 529 objects). Shapes and sizes come from `seed`: the same arguments
// give the same scene.
physics::Scene crowded_cockpit_scene(int loose_objects, uint32_t seed = 1);

// A pile: `objects` boxes and balls of 50 g (4 x 5 x 3 cm, 2 cm radius) in layers of a 5 x 4
// grid 7 cm apart, each layer 2 cm over the one below and off it by half a cell, each object a
// little off its place and turned (from `seed`), in a bin of four walls on a floor. They fall onto
// each other and settle into a heap. No hand.
physics::Scene pile_scene(int objects, uint32_t seed = 1);

// World time at which the bundled log holds the cup (lifted, between GRASP and RELEASE).
constexpr double kHoldTime_s = 4.0;

// Steps `world` through the bundled log up to kHoldTime_s. Returns the hand input it ends with,
// to keep the hand there. Throws std::runtime_error if the cup is not held at that moment.
physics::HandInput step_to_hold(physics::World& world);

}  // namespace vcockpit::bench
