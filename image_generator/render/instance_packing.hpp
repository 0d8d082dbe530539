#pragma once
// Instances -> per-instance GPU records grouped by unit mesh, so that each mesh is drawn with one
// instanced call. A capsule becomes a cylinder plus two sphere caps (uniformly scaled, so caps
// stay round whatever the capsule's proportions; hemispheres, their open side inside the
// cylinder). Reuses the records' capacity: no allocation
// once the instance count has peaked.

#include <array>
#include <memory>
#include <span>
#include <vector>

#include "image_generator/render/instance.hpp"
#include "image_generator/render/meshes.hpp"

namespace vcockpit::render {

// kCap: a capsule's end, the +z half of a coarser sphere (the other half is inside the
// capsule's cylinder: not drawn, the hands' 60 caps cost a quarter of the triangles of spheres).
// A tapered capsule is a kFrustum between two caps; a rounded box is kRoundedBox.
enum class UnitMesh { kBox, kSphere, kCylinder, kCap, kFrustum, kRoundedBox };
constexpr int kUnitMeshCount = 6;

// Matches the shader's per-instance attributes (see shaders.hpp).
struct InstanceRecord {
  std::array<float, 16> X_GO;            // column-major 4x4 pose
  std::array<float, 4> scale_highlight;  // unit mesh scale (x, y, z), highlight 0 or 1
  std::array<float, 4> rgba;
};
static_assert(sizeof(InstanceRecord) == 24 * sizeof(float), "tightly packed for the GPU");

struct MeshRange {
  int first = 0;
  int count = 0;
};

struct PackedInstances {
  std::vector<InstanceRecord> records;  // boxes, spheres, cylinders, caps, then model meshes
  std::array<MeshRange, kUnitMeshCount> ranges{};
  // the model meshes drawn (in the order first met) and each one's records
  std::vector<const MeshData*> model_meshes;
  // the same, to tell a mesh still alive from a new one made at a freed one's address
  std::vector<std::weak_ptr<const MeshData>> model_owners;
  std::vector<MeshRange> model_ranges;
  std::vector<int> model_next;  // (packing's scratch, kept for its capacity)

  const MeshRange& range(UnitMesh mesh) const { return ranges[static_cast<int>(mesh)]; }
};

void pack_instances(std::span<const Instance> instances, PackedInstances& packed);

}  // namespace vcockpit::render
