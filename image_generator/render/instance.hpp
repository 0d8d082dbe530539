#pragma once
// What the renderer draws: primitives with a pose, a size and a colour. Built by the caller
// every frame from the scene and its state; the renderer keeps no reference to it.

#include <Eigen/Geometry>
#include <array>
#include <memory>

#include "image_generator/render/meshes.hpp"

namespace vcockpit::render {

enum class Primitive { kBox, kSphere, kCylinder, kCapsule, kTaperedCapsule, kRoundedBox, kMesh };

struct Instance {
  Primitive primitive = Primitive::kBox;
  Eigen::Isometry3d X_GO = Eigen::Isometry3d::Identity();  // pose of the centroid frame in G
  // Metres. Box and rounded box: full extents (x, y, z). Sphere: (radius, 0, 0). Cylinder and
  // capsule: (radius, length, 0) along the object's z; a capsule's length excludes its end caps.
  // Tapered capsule (a finger's segment): (mean radius, length, 0), its radius narrowing from
  // the -z end to the +z end by kFrustumTaper (meshes.hpp), round caps of those radii.
  // Mesh: the scale of `mesh` (1, 1, 1: its vertices are in metres).
  Eigen::Vector3d size_m = Eigen::Vector3d::Zero();
  // 0..1; alpha below 1: translucent (glazing), blended over the opaque instances of its layer
  std::array<float, 4> rgba{0.6f, 0.6f, 0.6f, 1.0f};
  bool highlight = false;  // drawn brighter, as if glowing (held or hovered object)
  // Part of the background layer: the cockpit's shell and whatever else does not move. The
  // renderer draws these once into a cached image per eye and redraws it only when one of them
  // or the head changes (stereo_renderer.hpp).
  bool fixed = false;
  // kMesh: what to draw, in the object's frame; shared by every instance of the same model part
  // (the renderer uploads it once, the first time it is drawn)
  std::shared_ptr<const MeshData> mesh;
};

}  // namespace vcockpit::render
