#include "physics_node/fit/grip_scene_layout.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "physics_node/fit/shape_distance.hpp"

namespace vcockpit::fit {
namespace {

// The object's reach along a world direction.
double reach_m(const physics::Shape& shape, const Eigen::Isometry3d& X_GO,
               const Eigen::Vector3d& u_G) {
  return support_half_extent(shape, X_GO.linear().transpose() * u_G);
}

Eigen::Vector3d horizontal(double yaw_rad) {
  return Eigen::Vector3d(std::cos(yaw_rad), std::sin(yaw_rad), 0.0);
}

// The pedestal's yaw: along the object's axis that lies horizontal and that it reaches farthest
// along (a lying bar's axis, a box's longer side; the first on a tie: a sphere's x, 0). An object
// with no horizontal axis (not in a resting orientation) gets its widest horizontal direction,
// in 0.5 deg steps.
double pedestal_yaw_rad(const physics::Shape& shape, const Eigen::Isometry3d& X_GO) {
  double best_yaw = 0.0, best_reach = -1.0;
  for (int c = 0; c < 3; ++c) {
    const Eigen::Vector3d axis = X_GO.linear().col(c);
    if (std::abs(axis.z()) > 1e-9) continue;
    const double r = reach_m(shape, X_GO, axis);
    if (r > best_reach + 1e-12) {
      best_reach = r;
      best_yaw = std::atan2(axis.y(), axis.x());
    }
  }
  if (best_reach >= 0.0) return best_yaw;
  for (int k = 0; k < 360; ++k) {
    const double yaw = k * 0.5 * M_PI / 180.0;
    const double r = reach_m(shape, X_GO, horizontal(yaw));
    if (r > best_reach + 1e-12) {
      best_reach = r;
      best_yaw = yaw;
    }
  }
  return best_yaw;
}

// The least signed distance of the hand's links from a support box, and that link.
double clearance_m(const GripHand& hand, const SupportBox& box, hand::Link& nearest) {
  const physics::Shape shape = physics::Shape::box(box.size_m);
  const Eigen::Isometry3d X_GS = support_pose(box);
  double least_m = box_signed_distance(shape, X_GS, hand.palm_size_m, hand.X_GP);
  nearest = hand::Link::kPalm;
  for (int l = 1; l < hand::kLinkCount; ++l) {
    const auto k = static_cast<std::size_t>(l);
    const double d_m =
        capsule_signed_distance(shape, X_GS, hand.a_G[k], hand.b_G[k], hand.radius_m[k]);
    if (d_m < least_m) {
      least_m = d_m;
      nearest = static_cast<hand::Link>(l);
    }
  }
  return least_m;
}

}  // namespace

Eigen::Isometry3d support_pose(const SupportBox& box) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::AngleAxisd(box.yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  X.translation() = box.p_G;
  return X;
}

GripSceneLayout lay_out_supports(const GripHand& hand, const physics::Shape& shape,
                                 const Eigen::Isometry3d& X_GO, const LayoutRule& rule) {
  GripSceneLayout out;
  const Eigen::Vector3d p_GO = X_GO.translation();
  out.object_lowest_z_m = p_GO.z() - reach_m(shape, X_GO, Eigen::Vector3d::UnitZ());
  if (out.object_lowest_z_m <= 0.0) {
    char text[160];
    std::snprintf(text, sizeof text,
                  "the object's lowest point would be at z = %.4f m, not above the floor (z = 0)",
                  out.object_lowest_z_m);
    throw std::invalid_argument(text);
  }
  const double yaw = pedestal_yaw_rad(shape, X_GO);
  const double along_m = 2.0 * reach_m(shape, X_GO, horizontal(yaw));
  const double across_m = 2.0 * reach_m(shape, X_GO, horizontal(yaw + 0.5 * M_PI));

  double table_top_m = std::min(out.object_lowest_z_m - rule.min_pedestal_m,
                                hand_lowest_z_m(hand) - rule.hand_clearance_m);
  if (table_top_m - rule.table_size_m.z() >= 0.0) {
    SupportBox table;
    table.size_m = rule.table_size_m;
    table.p_G = Eigen::Vector3d(p_GO.x(), p_GO.y(), table_top_m - 0.5 * rule.table_size_m.z());
    out.table = table;
  } else {
    table_top_m = 0.0;  // the pedestal stands on the floor
  }
  const double height_m = out.object_lowest_z_m - table_top_m;
  out.pedestal.p_G = Eigen::Vector3d(p_GO.x(), p_GO.y(), table_top_m + 0.5 * height_m);
  out.pedestal.yaw_rad = yaw;
  // the footprint's share, narrowed while the hand at the moment reaches into the pedestal
  for (double share = rule.footprint_share;; share -= rule.footprint_step) {
    out.footprint_share = share;
    out.pedestal.size_m = Eigen::Vector3d(share * along_m, share * across_m, height_m);
    out.pedestal_clearance_m = clearance_m(hand, out.pedestal, out.pedestal_nearest_link);
    if (out.pedestal_clearance_m >= rule.pedestal_clearance_m ||
        share - rule.footprint_step < rule.min_footprint_share - 1e-9)
      break;
  }
  if (rule.extend_m > 0.0 && out.pedestal_clearance_m >= rule.pedestal_clearance_m) {
    // the sides' offsets from the object's centre along (+-along, +-across), grown in turn
    const Eigen::Vector3d u_along = horizontal(yaw), u_across = horizontal(yaw + 0.5 * M_PI);
    std::array<double, 4> side = {0.5 * out.pedestal.size_m.x(), 0.5 * out.pedestal.size_m.x(),
                                  0.5 * out.pedestal.size_m.y(), 0.5 * out.pedestal.size_m.y()};
    const std::array<double, 4> limit = {
        0.5 * along_m + rule.extend_m, 0.5 * along_m + rule.extend_m,
        0.5 * across_m + rule.extend_m, 0.5 * across_m + rule.extend_m};
    const auto box_of = [&](const std::array<double, 4>& s) {
      SupportBox box = out.pedestal;
      box.size_m.x() = s[0] + s[1];
      box.size_m.y() = s[2] + s[3];
      box.p_G.head<2>() = p_GO.head<2>() + (0.5 * (s[0] - s[1]) * u_along).head<2>() +
                          (0.5 * (s[2] - s[3]) * u_across).head<2>();
      return box;
    };
    std::array<bool, 4> open = {true, true, true, true};
    while (open[0] || open[1] || open[2] || open[3]) {
      for (std::size_t k = 0; k < 4; ++k) {
        if (!open[k]) continue;
        std::array<double, 4> next = side;
        next[k] = std::min(side[k] + rule.extend_step_m, limit[k]);
        hand::Link nearest = hand::Link::kPalm;
        if (next[k] <= side[k] ||
            clearance_m(hand, box_of(next), nearest) < rule.pedestal_clearance_m) {
          open[k] = false;
          continue;
        }
        side = next;
      }
    }
    out.pedestal = box_of(side);
    out.pedestal_clearance_m = clearance_m(hand, out.pedestal, out.pedestal_nearest_link);
  }
  return out;
}

}  // namespace vcockpit::fit
