#include "image_generator/render/instrument_panel.hpp"

#include "image_generator/render/text_overlay.hpp"

#include <algorithm>
#include <cmath>

namespace vcockpit::render {
namespace {

constexpr double kDegToRad = M_PI / 180.0;
const std::array<float, 4> kBezel{0.07f, 0.07f, 0.08f, 1.0f};
const std::array<float, 4> kFace{0.015f, 0.015f, 0.018f, 1.0f};
const std::array<float, 4> kWhite{0.92f, 0.92f, 0.90f, 1.0f};
const std::array<float, 4> kRed{0.90f, 0.12f, 0.10f, 1.0f};
const std::array<float, 4> kNeedle{1.0f, 0.62f, 0.15f, 1.0f};
const std::array<float, 4> kBug{1.0f, 0.35f, 0.85f, 1.0f};

// Depths above the face (m): each part on the one before, never at the same depth.
constexpr double kBezelDepth = 0.006, kFaceDepth = 0.002, kTickDepth = 0.0012, kNeedleDepth = 0.0012;
constexpr double kFaceTop = kBezelDepth + kFaceDepth;

Instance cylinder(const Eigen::Isometry3d& X_GF, double radius, double length, double z_centre,
                  const std::array<float, 4>& rgba) {
  Instance i;
  i.primitive = Primitive::kCylinder;
  i.X_GO = X_GF * Eigen::Translation3d(0, 0, z_centre);
  i.size_m = {radius, length, 0.0};
  i.rgba = rgba;
  return i;
}

// A box on the dial: `width` across, `length` along the direction `angle_deg` (clockwise from
// the top), its centre `r_centre` out from the dial's centre, `depth` thick, lying on z_base.
Instance radial_box(const Eigen::Isometry3d& X_GD, double angle_deg, double r_centre, double width,
                    double length, double depth, double z_base, const std::array<float, 4>& rgba) {
  const double a = angle_deg * kDegToRad;
  Instance i;
  i.primitive = Primitive::kBox;
  i.X_GO = X_GD * Eigen::Translation3d(r_centre * std::sin(a), r_centre * std::cos(a), z_base + depth / 2) *
           Eigen::AngleAxisd(-a, Eigen::Vector3d::UnitZ());
  i.size_m = {width, length, depth};
  i.rgba = rgba;
  return i;
}

void dial(const Eigen::Isometry3d& X_GD, double radius, std::vector<Instance>& out) {
  out.push_back(cylinder(X_GD, radius + 0.004, kBezelDepth, kBezelDepth / 2, kBezel));
  out.push_back(cylinder(X_GD, radius, kFaceDepth, kBezelDepth + kFaceDepth / 2, kFace));
}

}  // namespace

Eigen::Isometry3d PanelFace::at(const Eigen::Vector2d& at_m) const {
  return X_GF * Eigen::Translation3d(at_m.x(), at_m.y(), 0.0);
}

std::vector<std::string> InstrumentsSpec::systems() const {
  std::vector<std::string> out;
  for (const GaugeSpec& g : gauges) out.push_back(g.system);
  for (const HeadingSpec& h : headings) out.push_back(h.bug_system);
  for (const LampSpec& l : lamps) out.push_back(l.system);
  return out;
}

double needle_angle_deg(const GaugeSpec& g, double value) {
  if (!std::isfinite(value) || !(g.max > g.min)) return g.start_deg;
  const double s = std::clamp((value - g.min) / (g.max - g.min), 0.0, 1.0);
  return g.start_deg + s * (g.end_deg - g.start_deg);
}

void append_label(const PanelFace& face, const LabelSpec& label, std::vector<Instance>& out) {
  constexpr int kRows = 7, kColumns = 5, kAdvance = 6;
  const double px = label.height_m / kRows;
  const int n = static_cast<int>(label.text.size());
  const double width = (n * kAdvance - 1) * px;
  const std::array<float, 4> rgba{label.rgb[0], label.rgb[1], label.rgb[2], 1.0f};
  for (int k = 0; k < n; ++k) {
    const auto& rows = glyph_rows(label.text[static_cast<std::size_t>(k)]);
    for (int r = 0; r < kRows; ++r) {
      for (int c = 0; c < kColumns;) {
        if ((rows[static_cast<std::size_t>(r)] >> (kColumns - 1 - c) & 1) == 0) {
          ++c;
          continue;
        }
        int end = c;
        while (end < kColumns && (rows[static_cast<std::size_t>(r)] >> (kColumns - 1 - end) & 1) != 0) ++end;
        // the run's centre in the face (x right, y up), the label centred on `at`
        const double x = label.at_m.x() - width / 2 + (k * kAdvance + (c + end) / 2.0) * px;
        const double y = label.at_m.y() + label.height_m / 2 - (r + 0.5) * px;
        Instance i;
        i.primitive = Primitive::kBox;
        i.X_GO = face.at({x, y}) * Eigen::Translation3d(0, 0, 0.0004);
        i.size_m = {(end - c) * px, px, 0.0008};
        i.rgba = rgba;
        out.push_back(i);
        c = end;
      }
    }
  }
}

void append_instrument_faces(const InstrumentsSpec& spec, std::vector<Instance>& out) {
  for (const LabelSpec& l : spec.labels) append_label(spec.face, l, out);
  for (const Placard& p : spec.placards)
    for (const LabelSpec& l : p.labels) append_label(p.face, l, out);
  for (const GaugeSpec& g : spec.gauges) {
    const Eigen::Isometry3d X_GD = spec.face.at(g.at_m);
    const double r = g.radius_m;
    dial(X_GD, r, out);
    for (int k = 0; k < g.ticks; ++k) {
      const double value = g.ticks > 1 ? g.min + (g.max - g.min) * k / (g.ticks - 1) : g.min;
      out.push_back(radial_box(X_GD, needle_angle_deg(g, value), r - 0.2 * r, 0.0016, 0.18 * r,
                               kTickDepth, kFaceTop, kWhite));
    }
    if (std::isfinite(g.redline))
      out.push_back(radial_box(X_GD, needle_angle_deg(g, g.redline), r - 0.22 * r, 0.0022, 0.26 * r,
                               kTickDepth * 1.5, kFaceTop, kRed));
    // the hub, over the needle
    out.push_back(cylinder(X_GD, 0.12 * r, 0.002, kFaceTop + kNeedleDepth + 0.001, kBezel));
  }
  for (const HeadingSpec& h : spec.headings) {
    const Eigen::Isometry3d X_GD = spec.face.at(h.at_m);
    const double r = h.radius_m;
    dial(X_GD, r, out);
    for (int k = 0; k < 36; ++k) {  // every 10 deg, longer every 30
      const bool major = k % 3 == 0;
      out.push_back(radial_box(X_GD, 10.0 * k, r - (major ? 0.13 : 0.08) * r, 0.0012,
                               (major ? 0.16 : 0.08) * r, kTickDepth, kFaceTop, kWhite));
    }
    // the lubber line at the top and the aeroplane in the middle
    out.push_back(radial_box(X_GD, 0.0, r + 0.002, 0.003, 0.008, kTickDepth * 2, kFaceTop, kNeedle));
    out.push_back(radial_box(X_GD, 0.0, 0.0, 0.003, 0.024, kTickDepth, kFaceTop, kWhite));
    out.push_back(radial_box(X_GD, 90.0, 0.0, 0.003, 0.020, kTickDepth, kFaceTop, kWhite));
  }
  for (const LampSpec& l : spec.lamps) {  // a dark surround
    Instance i;
    i.primitive = Primitive::kBox;
    i.X_GO = spec.face.at(l.at_m) * Eigen::Translation3d(0, 0, 0.001);
    i.size_m = {l.size_m.x() + 0.004, l.size_m.y() + 0.004, 0.002};
    i.rgba = kBezel;
    out.push_back(i);
  }
}

void append_instrument_indications(const InstrumentsSpec& spec, const std::vector<double>& values,
                                   std::vector<Instance>& out) {
  std::size_t k = 0;
  const auto next = [&] { return k < values.size() ? values[k++] : (++k, std::nan("")); };
  for (const GaugeSpec& g : spec.gauges) {
    const double angle = needle_angle_deg(g, next());
    out.push_back(radial_box(spec.face.at(g.at_m), angle, 0.4 * g.radius_m, 0.0024, 0.84 * g.radius_m,
                             kNeedleDepth, kFaceTop + 0.0002, kNeedle));
  }
  for (const HeadingSpec& h : spec.headings) {
    const double bug = next();
    if (!std::isfinite(bug)) continue;
    // a notch on the rim at the bug's heading
    out.push_back(radial_box(spec.face.at(h.at_m), bug, h.radius_m - 0.045 * h.radius_m, 0.008,
                             0.09 * h.radius_m, kTickDepth * 2, kFaceTop + 0.0002, kBug));
  }
  for (const LampSpec& l : spec.lamps) {
    const double v = next();
    const bool lit = std::isfinite(v) && v > 0.5;
    Instance i;
    i.primitive = Primitive::kBox;
    i.X_GO = spec.face.at(l.at_m) * Eigen::Translation3d(0, 0, 0.002 + 0.0015);
    i.size_m = {l.size_m.x(), l.size_m.y(), 0.003};
    const float dim = lit ? 1.0f : 0.16f;
    i.rgba = {l.rgb[0] * dim, l.rgb[1] * dim, l.rgb[2] * dim, 1.0f};
    i.highlight = lit;
    out.push_back(i);
  }
}

}  // namespace vcockpit::render
