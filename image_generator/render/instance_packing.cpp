#include "image_generator/render/instance_packing.hpp"

namespace vcockpit::render {
namespace {

// The slot of `mesh` in packed.model_meshes, added if new.
std::size_t model_slot(PackedInstances& packed, const std::shared_ptr<const MeshData>& mesh) {
  for (std::size_t k = 0; k < packed.model_meshes.size(); ++k)
    if (packed.model_meshes[k] == mesh.get()) return k;
  packed.model_meshes.push_back(mesh.get());
  packed.model_owners.push_back(mesh);
  packed.model_ranges.push_back({});
  return packed.model_meshes.size() - 1;
}

void count(std::span<const Instance> instances, std::array<int, kUnitMeshCount>& counts,
           PackedInstances& packed) {
  counts.fill(0);
  packed.model_meshes.clear();
  packed.model_owners.clear();
  packed.model_ranges.clear();
  for (const Instance& instance : instances) {
    switch (instance.primitive) {
      case Primitive::kMesh:
        if (instance.mesh) ++packed.model_ranges[model_slot(packed, instance.mesh)].count;
        break;
      case Primitive::kBox:
        ++counts[0];
        break;
      case Primitive::kSphere:
        ++counts[1];
        break;
      case Primitive::kCylinder:
        ++counts[2];
        break;
      case Primitive::kCapsule:
        ++counts[2];
        counts[3] += 2;
        break;
      case Primitive::kTaperedCapsule:
        ++counts[4];
        counts[3] += 2;
        break;
      case Primitive::kRoundedBox:
        ++counts[5];
        break;
    }
  }
}

InstanceRecord make_record(const Eigen::Isometry3d& X_GO, const Eigen::Vector3d& scale,
                           const Instance& instance) {
  InstanceRecord record;
  Eigen::Map<Eigen::Matrix4f>(record.X_GO.data()) = X_GO.matrix().cast<float>();
  record.scale_highlight = {static_cast<float>(scale.x()), static_cast<float>(scale.y()),
                            static_cast<float>(scale.z()), instance.highlight ? 1.0f : 0.0f};
  record.rgba = instance.rgba;
  return record;
}

}  // namespace

void pack_instances(std::span<const Instance> instances, PackedInstances& packed) {
  std::array<int, kUnitMeshCount> counts;
  count(instances, counts, packed);
  int first = 0;
  for (int m = 0; m < kUnitMeshCount; ++m) {
    packed.ranges[m] = {first, counts[m]};
    first += counts[m];
  }
  std::vector<int>& model_next = packed.model_next;
  model_next.clear();
  for (MeshRange& range : packed.model_ranges) {
    range.first = first;
    model_next.push_back(first);
    first += range.count;
  }
  packed.records.resize(static_cast<size_t>(first));  // no allocation within capacity

  std::array<int, kUnitMeshCount> next{};
  for (int m = 0; m < kUnitMeshCount; ++m) next[m] = packed.ranges[m].first;
  auto put = [&](UnitMesh mesh, const Eigen::Isometry3d& X_GO, const Eigen::Vector3d& scale,
                 const Instance& instance) {
    packed.records[static_cast<size_t>(next[static_cast<int>(mesh)]++)] =
        make_record(X_GO, scale, instance);
  };
  for (const Instance& instance : instances) {
    const Eigen::Vector3d& s = instance.size_m;
    switch (instance.primitive) {
      case Primitive::kMesh:
        if (instance.mesh) {
          const std::size_t k = model_slot(packed, instance.mesh);
          packed.records[static_cast<size_t>(model_next[k]++)] =
              make_record(instance.X_GO, s, instance);
        }
        break;
      case Primitive::kBox:
        put(UnitMesh::kBox, instance.X_GO, s, instance);
        break;
      case Primitive::kSphere:
        put(UnitMesh::kSphere, instance.X_GO, Eigen::Vector3d::Constant(s.x()), instance);
        break;
      case Primitive::kCylinder:
        put(UnitMesh::kCylinder, instance.X_GO, {s.x(), s.x(), s.y()}, instance);
        break;
      case Primitive::kCapsule: {
        const double half_length_m = 0.5 * s.y();
        put(UnitMesh::kCylinder, instance.X_GO, {s.x(), s.x(), s.y()}, instance);
        // the +z cap as it is, the -z cap turned half a turn about x to face -z
        put(UnitMesh::kCap, instance.X_GO * Eigen::Translation3d(0.0, 0.0, half_length_m),
            Eigen::Vector3d::Constant(s.x()), instance);
        put(UnitMesh::kCap,
            instance.X_GO * Eigen::Translation3d(0.0, 0.0, -half_length_m) *
                Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()),
            Eigen::Vector3d::Constant(s.x()), instance);
        break;
      }
      case Primitive::kTaperedCapsule: {
        // the mean radius s.x(): the -z end's radius r0 and the +z end's taper * r0
        const double half_length_m = 0.5 * s.y();
        const double r0 = 2.0 * s.x() / (1.0 + kFrustumTaper), r1 = kFrustumTaper * r0;
        put(UnitMesh::kFrustum, instance.X_GO, {r0, r0, s.y()}, instance);
        put(UnitMesh::kCap, instance.X_GO * Eigen::Translation3d(0.0, 0.0, half_length_m),
            Eigen::Vector3d::Constant(r1), instance);
        put(UnitMesh::kCap,
            instance.X_GO * Eigen::Translation3d(0.0, 0.0, -half_length_m) *
                Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()),
            Eigen::Vector3d::Constant(r0), instance);
        break;
      }
      case Primitive::kRoundedBox:
        put(UnitMesh::kRoundedBox, instance.X_GO, s, instance);
        break;
    }
  }
}

}  // namespace vcockpit::render
