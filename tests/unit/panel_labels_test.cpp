// The panel's labels (config/instruments.yaml) read in the head-mounted display: at the design
// eye (config/hmd.yaml), every label is in an eye's 1280 x 720 image and at least 7 px tall in
// each image that holds it (the 5 x 7 panel font's rows a pixel each). Each lies on the panel's
// face, clear of the other labels, of the instruments (dials, bezels, lamps and their
// surrounds) and of what stands on it (config/cockpit.yaml: the controls' parts where they rest,
// their annunciators). Every control on the panel has a label within 3 cm. The pedestal's
// placard the same, for a pilot glancing down at it from the design eye.

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "image_generator/node/hmd_yaml.hpp"
#include "image_generator/node/instruments_yaml.hpp"
#include "image_generator/render/camera.hpp"
#include "physics_node/config/scene_config.hpp"
#include "physics_node/physics/broadphase.hpp"
#include "physics_node/physics/world.hpp"

namespace vcockpit {
namespace {

std::string source_dir() {
  const char* dir = std::getenv("VCOCKPIT_SOURCE_DIR");
  return dir != nullptr ? dir : ".";
}

// A rectangle on the face (m, x right, y up).
struct FaceBox {
  std::string what;
  Eigen::Vector2d lo, hi;
};

bool overlap(const FaceBox& a, const FaceBox& b) {
  return a.lo.x() < b.hi.x() && b.lo.x() < a.hi.x() && a.lo.y() < b.hi.y() && b.lo.y() < a.hi.y();
}

FaceBox label_box(const render::LabelSpec& l) {
  // the font's cell: 5 columns lit of a 6-column advance, 7 rows (instrument_panel.cpp)
  const double cell_m = l.height_m / 7.0;
  const double half_w = 0.5 * (static_cast<double>(l.text.size()) * 6 - 1) * cell_m;
  const Eigen::Vector2d half(half_w, 0.5 * l.height_m);
  return {"label " + l.text, l.at_m - half, l.at_m + half};
}

// A circle (a dial) against a box: the nearest point of the box to its centre.
bool overlap(const Eigen::Vector2d& centre, double radius_m, const FaceBox& box) {
  const Eigen::Vector2d nearest = centre.cwiseMax(box.lo).cwiseMin(box.hi);
  return (nearest - centre).norm() < radius_m;
}

// What stands on the face, seen straight on: the box round the extremes of each object within
// 5 cm in front of it and smaller than 10 x 10 cm there (the controls' parts where they rest,
// their annunciators; not the panel's slab or the glareshield), by its name; with `within`,
// only those that reach into that box of the face.
std::vector<FaceBox> things_on_the_face(const render::PanelFace& face,
                                        const FaceBox* within = nullptr) {
  const physics::World world(load_scene(source_dir() + "/config/cockpit.yaml"));
  const physics::Scene& scene = world.scene();
  const Eigen::Isometry3d X_FG = face.X_GF.inverse();
  std::vector<FaceBox> out;
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const physics::Aabb box_F =
        physics::shape_aabb(scene.objects[i].shape, X_FG * world.bodies()[i].X_GO);
    const FaceBox box{scene.objects[i].name, box_F.lo.head<2>(), box_F.hi.head<2>()};
    const double nearest_out_m = box_F.lo.z(), farthest_out_m = box_F.hi.z();
    const Eigen::Vector2d extent = box.hi - box.lo;
    if (nearest_out_m < 0.05 && farthest_out_m > 0.0 && extent.x() < 0.1 && extent.y() < 0.1 &&
        (within == nullptr || overlap(box, *within)))
      out.push_back(box);
  }
  return out;
}

// Each label's height in the eyes' images with the head at X_GHead: at least 7 px in each image
// that holds it, and in one image at least. The smallest is printed with its label.
void check_label_heights(const render::PanelFace& face, const std::vector<render::LabelSpec>& labels,
                           const HmdSetup& hmd, const Eigen::Isometry3d& X_GHead) {
  double smallest_px = 1e9;
  std::string smallest;
  for (const render::LabelSpec& l : labels) {
    int seen_by = 0;  // the eyes whose image holds it (the left eye's reaches farther left)
    for (const render::Eye eye : {render::Eye::kLeft, render::Eye::kRight}) {
      const Eigen::Vector2d up(0.0, 0.5 * l.height_m);
      Eigen::Vector2d top, bottom;
      const Eigen::Vector3d top_G = face.at(l.at_m + up).translation();
      const Eigen::Vector3d bottom_G = face.at(l.at_m - up).translation();
      if (!render::project_to_pixel(hmd.hmd, eye, X_GHead, top_G, top) ||
          !render::project_to_pixel(hmd.hmd, eye, X_GHead, bottom_G, bottom))
        continue;
      ++seen_by;
      const double px = (top - bottom).norm();
      EXPECT_GE(px, 7.0) << l.text << " at (" << l.at_m.transpose() << ")";
      if (px < smallest_px) {
        smallest_px = px;
        smallest = l.text;
      }
    }
    EXPECT_GE(seen_by, 1) << l.text << " is in neither eye's image";
  }
  std::printf("smallest label: %s, %.2f px tall\n", smallest.c_str(), smallest_px);
}

// The gap between two boxes on a face (0 when they touch or overlap).
double gap_m(const FaceBox& a, const FaceBox& b) {
  return (a.lo - b.hi).cwiseMax(b.lo - a.hi).cwiseMax(Eigen::Vector2d::Zero()).norm();
}

// Whether the segment from `from_G` to `to_G` passes through the box round `shape` placed at
// X_GO (the slab test in the shape's frame: a lever's box exactly, a round part's bounding box).
bool segment_hits(const physics::Shape& shape, const Eigen::Isometry3d& X_GO,
                  const Eigen::Vector3d& from_G, const Eigen::Vector3d& to_G) {
  const physics::Aabb box = physics::shape_aabb(shape, Eigen::Isometry3d::Identity());
  const Eigen::Vector3d a = X_GO.inverse() * from_G, d = X_GO.inverse() * to_G - a;
  double t0 = 0.0, t1 = 1.0;
  for (int k = 0; k < 3; ++k) {
    if (std::abs(d[k]) < 1e-12) {
      if (a[k] < box.lo[k] || a[k] > box.hi[k]) return false;
      continue;
    }
    double near = (box.lo[k] - a[k]) / d[k], far = (box.hi[k] - a[k]) / d[k];
    if (near > far) std::swap(near, far);
    t0 = std::max(t0, near);
    t1 = std::min(t1, far);
    if (t0 > t1) return false;
  }
  return true;
}

// The pedestal's placards, read by a pilot who turns from the design eye's gaze to look down at
// the quadrant (the head where the design eye puts it, its forward axis on the top placard's
// centre, level): each label 7 px tall or more, on its placard, clear of the others and of the
// levers where they rest, and in full view: no object of the cockpit between either eye and its
// corners or centre. Each lever has a label within 6 cm and its name within 8 cm, and the
// levers' names and positions are all there.
TEST(PedestalLabels, EveryLabelReadsAtAGlanceInFullViewAndClearsTheLevers) {
  const render::InstrumentsSpec spec = load_instruments(source_dir() + "/config/instruments.yaml");
  const HmdSetup hmd = load_hmd_config(source_dir() + "/config/hmd.yaml");
  ASSERT_EQ(spec.placards.size(), 2u);
  const Eigen::Vector3d head_G = hmd.X_GHead.translation();
  const Eigen::Vector3d to_top = spec.placards[0].face.X_GF.translation() - head_G;
  const double yaw = std::atan2(to_top.y(), to_top.x());
  const double pitch = std::atan2(-to_top.z(), to_top.head<2>().norm());  // + looks down
  const Eigen::Isometry3d X_GHead = Eigen::Translation3d(head_G) *
                                    Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                                    Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY());
  std::printf("glancing at the pedestal: yaw %.1f deg, pitch %.1f deg down, %.2f m away\n",
              yaw * 180 / M_PI, pitch * 180 / M_PI, to_top.norm());

  const physics::World world(load_scene(source_dir() + "/config/cockpit.yaml"));
  const physics::Scene& scene = world.scene();
  const int pedestal = scene.find_object("left_pedestal");
  ASSERT_GE(pedestal, 0);
  const int throttle = scene.find_object("throttle"), flaps = scene.find_object("flaps");
  ASSERT_GE(throttle, 0);
  ASSERT_GE(flaps, 0);
  std::map<std::string, Eigen::Vector3d> label_at_G;  // each text's centre
  std::vector<std::vector<Eigen::Vector3d>> label_points_G;
  for (const render::Placard& placard : spec.placards) {
    SCOPED_TRACE(placard.name);
    check_label_heights(placard.face, placard.labels, hmd, X_GHead);
    const FaceBox face{"placard", -0.5 * placard.size_m, 0.5 * placard.size_m};
    std::vector<FaceBox> labels;
    for (const render::LabelSpec& l : placard.labels) labels.push_back(label_box(l));
    const std::vector<FaceBox> on_it = things_on_the_face(placard.face, &face);
    for (std::size_t i = 0; i < labels.size(); ++i) {
      const FaceBox& a = labels[i];
      EXPECT_TRUE(a.lo.x() >= face.lo.x() && a.lo.y() >= face.lo.y() &&
                  a.hi.x() <= face.hi.x() && a.hi.y() <= face.hi.y())
          << a.what << " leaves the placard";
      for (std::size_t j = i + 1; j < labels.size(); ++j)
        EXPECT_FALSE(overlap(a, labels[j])) << a.what << " on " << labels[j].what;
      for (const FaceBox& b : on_it) EXPECT_FALSE(overlap(a, b)) << a.what << " on " << b.what;
      // in full view: its centre and corners, 1 mm off the face, seen by both eyes
      std::vector<Eigen::Vector3d> points;
      for (const Eigen::Vector2d& p :
           {Eigen::Vector2d(0.5 * (a.lo + a.hi)), a.lo, a.hi, Eigen::Vector2d(a.lo.x(), a.hi.y()),
            Eigen::Vector2d(a.hi.x(), a.lo.y())})
        points.push_back(placard.face.at(p) * Eigen::Vector3d(0, 0, 0.001));
      for (const render::Eye eye : {render::Eye::kLeft, render::Eye::kRight}) {
        const Eigen::Vector3d eye_G = render::eye_pose(hmd.hmd, eye, X_GHead).translation();
        for (const Eigen::Vector3d& p : points) {
          for (std::size_t o = 0; o < scene.objects.size(); ++o) {
            if (static_cast<int>(o) == pedestal) continue;  // what the placard is painted on
            EXPECT_FALSE(segment_hits(scene.objects[o].shape, world.bodies()[o].X_GO, eye_G, p))
                << scene.objects[o].name << " hides " << a.what << " at " << p.transpose();
          }
        }
      }
      label_at_G[placard.labels[i].text] = points[0];
      label_points_G.push_back(points);
    }
  }
  // each lever's labels near it: the nearest within 6 cm, its name within 8 cm
  for (const auto& [lever, name] : {std::pair{throttle, "THROTTLE"}, std::pair{flaps, "FLAPS"}}) {
    const physics::Aabb box = physics::shape_aabb(scene.objects[lever].shape, world.bodies()[lever].X_GO);
    const auto off_m = [&](const Eigen::Vector3d& p) {
      return (box.lo - p).cwiseMax(p - box.hi).cwiseMax(Eigen::Vector3d::Zero()).norm();
    };
    double nearest_m = 1e9;
    for (const auto& points : label_points_G)
      for (const Eigen::Vector3d& p : points) nearest_m = std::min(nearest_m, off_m(p));
    EXPECT_LE(nearest_m, 0.06) << scene.objects[lever].name;
    ASSERT_TRUE(label_at_G.count(name)) << name;
    EXPECT_LE(off_m(label_at_G[name]), 0.08) << name << " is " << off_m(label_at_G[name]) * 1e3
                                              << " mm from its lever";
  }
  for (const char* text : {"THROTTLE", "FULL", "IDLE", "CUT", "FLAPS", "UP", "APP", "LDG"})
    EXPECT_TRUE(label_at_G.count(text)) << text;
}

TEST(PanelLabels, EveryLabelReadsAtTheDesignEyeAndClearsTheInstrumentsAndControls) {
  const render::InstrumentsSpec spec = load_instruments(source_dir() + "/config/instruments.yaml");
  const HmdSetup hmd = load_hmd_config(source_dir() + "/config/hmd.yaml");
  ASSERT_EQ(hmd.hmd.width_px, 1280);
  ASSERT_EQ(hmd.hmd.height_px, 720);

  check_label_heights(spec.face, spec.labels, hmd, hmd.X_GHead);

  // on the face (the instrument panel's slab face: 1.10 m x 0.35 m), clear of everything else
  const FaceBox panel{"panel", {-0.55, -0.175}, {0.55, 0.175}};
  std::vector<FaceBox> labels;
  for (const render::LabelSpec& l : spec.labels) labels.push_back(label_box(l));
  std::vector<FaceBox> others = things_on_the_face(spec.face);
  const std::size_t on_the_face = others.size();
  for (const render::LampSpec& l : spec.lamps) {
    const Eigen::Vector2d half = 0.5 * l.size_m + Eigen::Vector2d::Constant(0.002);  // its surround
    others.push_back({"lamp " + l.system, l.at_m - half, l.at_m + half});
  }
  for (std::size_t i = 0; i < labels.size(); ++i) {
    const FaceBox& a = labels[i];
    EXPECT_TRUE(a.lo.x() >= panel.lo.x() && a.lo.y() >= panel.lo.y() && a.hi.x() <= panel.hi.x() &&
                a.hi.y() <= panel.hi.y())
        << a.what << " leaves the face";
    for (std::size_t j = i + 1; j < labels.size(); ++j)
      EXPECT_FALSE(overlap(a, labels[j])) << a.what << " on " << labels[j].what;
    for (const FaceBox& b : others) EXPECT_FALSE(overlap(a, b)) << a.what << " on " << b.what;
    // a dial's bezel reaches 4 mm past its face; the heading display's lubber mark 10 mm
    for (const render::GaugeSpec& g : spec.gauges)
      EXPECT_FALSE(overlap(g.at_m, g.radius_m + 0.004, a)) << a.what << " on gauge " << g.system;
    for (const render::HeadingSpec& h : spec.headings)
      EXPECT_FALSE(overlap(h.at_m, h.radius_m + 0.010, a)) << a.what << " on the heading display";
  }
  // the panel's nine controls (the pedestal's levers are not on it) and the four annunciators
  // that light with them (landing lights, fuel pump, engine start, gear)
  std::string names;
  for (std::size_t k = 0; k < on_the_face; ++k) names += " " + others[k].what;
  std::printf("%zu objects stand on the face:%s\n", on_the_face, names.c_str());
  EXPECT_EQ(on_the_face, 13u);

  // every control on the panel is named: a label within 3 cm of where its part rests
  const physics::Scene scene = load_scene(source_dir() + "/config/cockpit.yaml");
  for (std::size_t k = 0; k < on_the_face; ++k) {
    const FaceBox& part = others[k];
    if (scene.find_control(part.what) < 0) continue;  // an annunciator
    double nearest_m = 1e9;
    std::string nearest;
    for (const FaceBox& l : labels) {
      if (gap_m(l, part) < nearest_m) {
        nearest_m = gap_m(l, part);
        nearest = l.what;
      }
    }
    EXPECT_LE(nearest_m, 0.03) << part.what << ": the nearest label, " << nearest << ", is "
                               << nearest_m * 1e3 << " mm off";
  }
  std::set<std::string> texts;
  for (const render::LabelSpec& l : spec.labels) texts.insert(l.text);
  for (const char* name : {"LDG LT", "FUEL", "START", "CAUTION", "AVIONICS", "NAV", "HDG", "UP",
                           "DN", "GEAR", "VOR", "GPS", "LOC", "APP"})
    EXPECT_TRUE(texts.count(name)) << name;
}

}  // namespace
}  // namespace vcockpit
