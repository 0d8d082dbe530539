#pragma once
// The panel's live instruments as render instances: round gauges with a needle, a heading
// display with its bug, and lamps (gear lights, annunciators). What does not move with a value
// (bezels, faces, ticks, hubs, the lubber line) goes in the cached static layer; needles, the
// bug and the lamps in the moving layer, so a needle costs a few boxes a frame and the static
// layer is never redrawn for it (stereo_renderer.hpp).
//
// Each instrument sits on a panel face frame F: z out of the panel toward the pilot, x to the
// pilot's right, y up the face; `at` is its centre there (m). A gauge's angles are clockwise from
// 12 o'clock as the pilot sees them. Values come bound by index (the caller maps the aircraft's
// system names to them); a value that is not known (NaN) puts a needle at its range's start and
// a lamp out.

#include <Eigen/Geometry>

#include <array>
#include <string>
#include <vector>

#include "image_generator/render/instance.hpp"

namespace vcockpit::render {

struct PanelFace {
  Eigen::Isometry3d X_GF = Eigen::Isometry3d::Identity();
  // The frame of a point `at` (m, x right, y up) on the face.
  Eigen::Isometry3d at(const Eigen::Vector2d& at_m) const;
};

struct GaugeSpec {
  std::string system;        // the value it shows (config/aircraft.yaml's name)
  Eigen::Vector2d at_m = Eigen::Vector2d::Zero();
  double radius_m = 0.035;
  double min = 0.0, max = 100.0;
  double start_deg = -135.0, end_deg = 135.0;  // where min and max point
  int ticks = 11;                              // major ticks, min to max inclusive
  double redline = std::nan("");               // a red tick there (NaN: none)
};

struct HeadingSpec {
  std::string bug_system;    // the bug's heading (deg, clockwise from the top)
  Eigen::Vector2d at_m = Eigen::Vector2d::Zero();
  double radius_m = 0.045;
};

struct LampSpec {
  std::string system;        // lit while its value is above 0.5
  Eigen::Vector2d at_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d size_m{0.014, 0.014};
  std::array<float, 3> rgb{0.1f, 0.9f, 0.2f};
};

// A label painted on the face: the 5x7 font of text_overlay.hpp, each row's run of lit pixels a
// thin box, `height_m` the glyphs' height, centred on `at`.
struct LabelSpec {
  std::string text;
  Eigen::Vector2d at_m = Eigen::Vector2d::Zero();
  double height_m = 0.008;
  std::array<float, 3> rgb{0.85f, 0.85f, 0.82f};
};

// Labels on another face of the cockpit than the panel's (the pedestal's top, by its levers):
// the face's frame as PanelFace's, its extent centred on the origin, its labels.
struct Placard {
  std::string name;
  PanelFace face;
  Eigen::Vector2d size_m = Eigen::Vector2d::Zero();
  std::vector<LabelSpec> labels;
};

struct InstrumentsSpec {
  PanelFace face;
  std::vector<LabelSpec> labels;
  std::vector<Placard> placards;
  std::vector<GaugeSpec> gauges;
  std::vector<HeadingSpec> headings;
  std::vector<LampSpec> lamps;
  // every system named above, in order: gauges, headings, lamps (the values' order)
  std::vector<std::string> systems() const;
};

// The static layer's instances (appended), the labels and the placards' with them.
void append_instrument_faces(const InstrumentsSpec& spec, std::vector<Instance>& out);
// One label's boxes (appended): a box per run of lit pixels in a glyph row.
void append_label(const PanelFace& face, const LabelSpec& label, std::vector<Instance>& out);
// The moving layer's (appended): `values` in spec.systems()'s order (shorter: the rest unknown).
void append_instrument_indications(const InstrumentsSpec& spec, const std::vector<double>& values,
                                   std::vector<Instance>& out);
// Where a gauge's needle points for `value` (deg, clockwise from 12 o'clock): the range's
// start for NaN, clamped to the range.
double needle_angle_deg(const GaugeSpec& gauge, double value);

}  // namespace vcockpit::render
