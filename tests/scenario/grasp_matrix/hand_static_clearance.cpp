#include "tests/scenario/grasp_matrix/hand_static_clearance.hpp"

#include <fcl/narrowphase/collision.h>

#include <stdexcept>

#include "physics_node/physics/fcl_geometry.hpp"

namespace vcockpit::test {

struct HandStaticClearance::Impl {
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> statics;
  std::vector<int> static_index;  // scene object index of each
  std::array<std::unique_ptr<fcl::CollisionObjectd>, hand::kLinkCount> links;
  std::array<Eigen::Isometry3d, hand::kLinkCount> X_LC;  // link frame -> FCL geometry frame
};

HandStaticClearance::HandStaticClearance(const physics::Scene& scene, const hand::HandModel& hand)
    : impl_(std::make_unique<Impl>()) {
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const physics::ObjectSpec& o = scene.objects[i];
    if (o.dynamic) continue;
    auto object = std::make_unique<fcl::CollisionObjectd>(physics::fcl_geometry(o.shape, /*moving=*/false), o.X_GO);
    object->computeAABB();
    impl_->statics.push_back(std::move(object));
    impl_->static_index.push_back(static_cast<int>(i));
  }
  // the palm link's frame is the palm box's centre (X_HL[palm] = X_HP)
  impl_->X_LC[0] = Eigen::Isometry3d::Identity();
  impl_->links[0] = std::make_unique<fcl::CollisionObjectd>(
      std::make_shared<fcl::Boxd>(hand.palm_size_m));
  for (int l = 1; l < hand::kLinkCount; ++l) {
    const hand::Capsule& c = hand.capsules[static_cast<std::size_t>(l)];
    // FCL's capsule is centred on its own z; the phalanx runs along x_L from 0 to length
    Eigen::Isometry3d X_LC = Eigen::Isometry3d::Identity();
    X_LC.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();
    X_LC.translation() = Eigen::Vector3d(0.5 * c.length_m, 0, 0);
    impl_->X_LC[static_cast<std::size_t>(l)] = X_LC;
    impl_->links[static_cast<std::size_t>(l)] = std::make_unique<fcl::CollisionObjectd>(
        std::make_shared<fcl::Capsuled>(c.radius_m, c.length_m));
  }
}

HandStaticClearance::~HandStaticClearance() = default;

Penetration HandStaticClearance::deepest(
    const std::array<Eigen::Isometry3d, hand::kLinkCount>& X_GL) {
  Penetration out;
  fcl::CollisionRequestd request(4, /*enable_contact=*/true);
  for (int l = 0; l < hand::kLinkCount; ++l) {
    fcl::CollisionObjectd& link = *impl_->links[static_cast<std::size_t>(l)];
    link.setTransform(X_GL[static_cast<std::size_t>(l)] * impl_->X_LC[static_cast<std::size_t>(l)]);
    link.computeAABB();
    for (std::size_t s = 0; s < impl_->statics.size(); ++s) {
      if (!link.getAABB().overlap(impl_->statics[s]->getAABB())) continue;
      fcl::CollisionResultd result;
      fcl::collide(&link, impl_->statics[s].get(), request, result);
      for (std::size_t c = 0; c < result.numContacts(); ++c) {
        const double depth = result.getContact(c).penetration_depth;
        if (depth > out.depth_m) out = {depth, l, impl_->static_index[s]};
      }
    }
  }
  return out;
}

}  // namespace vcockpit::test
