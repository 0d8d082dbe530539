// The panel's labels (config/instruments.yaml) read in the head-mounted display: at the design
// eye (config/hmd.yaml), every label is in an eye's 1280 x 720 image and at least 7 px tall in
// each image that holds it (the 5 x 7 panel font's rows a pixel each). Each lies on the panel's
// face, clear of the other labels, of the instruments (dials, bezels, lamps and their
// surrounds) and of what stands on it (config/cockpit.yaml: the controls' parts where they rest,
// their annunciators). Every control on the panel has a label within 3 cm.

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
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
// their annunciators; not the panel's slab or the glareshield), by its name.
std::vector<FaceBox> things_on_the_face(const render::PanelFace& face) {
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
    if (nearest_out_m < 0.05 && farthest_out_m > 0.0 && extent.x() < 0.1 && extent.y() < 0.1)
      out.push_back(box);
  }
  return out;
}

TEST(PanelLabels, EveryLabelReadsAtTheDesignEyeAndClearsTheInstrumentsAndControls) {
  const render::InstrumentsSpec spec = load_instruments(source_dir() + "/config/instruments.yaml");
  const HmdSetup hmd = load_hmd_config(source_dir() + "/config/hmd.yaml");
  ASSERT_EQ(hmd.hmd.width_px, 1280);
  ASSERT_EQ(hmd.hmd.height_px, 720);

  double smallest_px = 1e9;
  std::string smallest;
  for (const render::LabelSpec& l : spec.labels) {
    int seen_by = 0;  // the eyes whose image holds it (the left eye's reaches farther left)
    for (const render::Eye eye : {render::Eye::kLeft, render::Eye::kRight}) {
      const Eigen::Vector2d up(0.0, 0.5 * l.height_m);
      Eigen::Vector2d top, bottom;
      const Eigen::Vector3d top_G = spec.face.at(l.at_m + up).translation();
      const Eigen::Vector3d bottom_G = spec.face.at(l.at_m - up).translation();
      if (!render::project_to_pixel(hmd.hmd, eye, hmd.X_GHead, top_G, top) ||
          !render::project_to_pixel(hmd.hmd, eye, hmd.X_GHead, bottom_G, bottom))
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
  std::printf("smallest label at the design eye: %s, %.2f px tall\n", smallest.c_str(),
              smallest_px);

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
      const Eigen::Vector2d gap =
          (l.lo - part.hi).cwiseMax(part.lo - l.hi).cwiseMax(Eigen::Vector2d::Zero());
      if (gap.norm() < nearest_m) {
        nearest_m = gap.norm();
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
