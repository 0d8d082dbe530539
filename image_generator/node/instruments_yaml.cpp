#include "image_generator/node/instruments_yaml.hpp"

#include <cmath>

#include "common/yaml_config.hpp"

namespace vcockpit {
namespace {

Eigen::Vector3d vec3(const ConfigNode& node) {
  const auto v = node.as_doubles<3>();
  return {v[0], v[1], v[2]};
}

Eigen::Vector2d vec2(const ConfigNode& node) {
  const auto v = node.as_doubles<2>();
  return {v[0], v[1]};
}

std::string system_of(const ConfigNode& node, const char* key) {
  const std::string s = node.get_string(key);
  if (s.empty() || s.size() > 64) node[key].fail("a system's name (1 to 64 characters)");
  return s;
}

double positive(const ConfigNode& node, const char* key, double fallback) {
  const double v = node.get_double(key, fallback);
  if (!(v > 0.0 && v < 1.0)) node[key].fail("must be within 0..1 m");
  return v;
}

std::array<float, 3> colour(const ConfigNode& node) {
  const auto c = node.as_doubles<3>();
  for (double x : c)
    if (x < 0 || x > 1) node.fail("colour components are within 0..1");
  return {static_cast<float>(c[0]), static_cast<float>(c[1]), static_cast<float>(c[2])};
}

// {origin, right, up}: a face's frame (z out of it, right x up); the keys checked by the caller
render::PanelFace face_of(const ConfigNode& node) {
  const Eigen::Vector3d right = vec3(node["right"]);
  const Eigen::Vector3d up = vec3(node["up"]);
  if (std::abs(right.norm() - 1.0) > 1e-3 || std::abs(up.norm() - 1.0) > 1e-3 ||
      std::abs(right.dot(up)) > 1e-3)
    node.fail("right and up must be unit vectors at right angles");
  Eigen::Matrix3d R;
  R.col(0) = right.normalized();
  R.col(1) = up.normalized();
  R.col(2) = R.col(0).cross(R.col(1));
  render::PanelFace face;
  face.X_GF.linear() = R;
  face.X_GF.translation() = vec3(node["origin"]);
  return face;
}

// [{text, at, height, color?}]
std::vector<render::LabelSpec> labels_of(const ConfigNode& labels) {
  std::vector<render::LabelSpec> out;
  for (const ConfigNode& l : labels.elements()) {
    l.expect_keys({"text", "at", "height", "color"});
    render::LabelSpec s;
    s.text = l.get_string("text");
    if (s.text.empty() || s.text.size() > 24) l["text"].fail("1 to 24 characters");
    for (char c : s.text)
      if (c < 32 || c > 126) l["text"].fail("printable ASCII only (the panel font's)");
    s.at_m = vec2(l["at"]);
    s.height_m = l.get_double("height", 0.008);
    if (!(s.height_m >= 0.003 && s.height_m <= 0.05)) l["height"].fail("within 0.003..0.05 m");
    if (auto c = l.find("color")) s.rgb = colour(*c);
    out.push_back(s);
  }
  return out;
}

}  // namespace

render::InstrumentsSpec parse_instruments(const ConfigNode& root) {
  root.expect_keys({"panel", "gauges", "headings", "lamps", "labels", "placards"});
  render::InstrumentsSpec spec;
  root["panel"].expect_keys({"origin", "right", "up"});
  spec.face = face_of(root["panel"]);
  if (auto gauges = root.find("gauges")) {
    for (const ConfigNode& g : gauges->elements()) {
      g.expect_keys({"system", "at", "radius", "range", "sweep_deg", "ticks", "redline"});
      render::GaugeSpec s;
      s.system = system_of(g, "system");
      s.at_m = vec2(g["at"]);
      s.radius_m = positive(g, "radius", 0.035);
      const auto range = g["range"].as_doubles<2>();
      if (!(range[1] > range[0])) g["range"].fail("[min, max] with max > min");
      s.min = range[0];
      s.max = range[1];
      if (auto sweep = g.find("sweep_deg")) {
        const auto a = sweep->as_doubles<2>();
        if (std::abs(a[1] - a[0]) > 360.0 || a[1] == a[0]) sweep->fail("[start, end], at most 360 deg apart");
        s.start_deg = a[0];
        s.end_deg = a[1];
      }
      s.ticks = static_cast<int>(g.get_int("ticks", 11));
      if (s.ticks < 2 || s.ticks > 41) g["ticks"].fail("2 to 41");
      if (auto red = g.find("redline")) s.redline = red->as_double();
      spec.gauges.push_back(s);
    }
  }
  if (auto headings = root.find("headings")) {
    for (const ConfigNode& h : headings->elements()) {
      h.expect_keys({"bug", "at", "radius"});
      render::HeadingSpec s;
      s.bug_system = system_of(h, "bug");
      s.at_m = vec2(h["at"]);
      s.radius_m = positive(h, "radius", 0.045);
      spec.headings.push_back(s);
    }
  }
  if (auto lamps = root.find("lamps")) {
    for (const ConfigNode& l : lamps->elements()) {
      l.expect_keys({"system", "at", "size", "color"});
      render::LampSpec s;
      s.system = system_of(l, "system");
      s.at_m = vec2(l["at"]);
      if (auto size = l.find("size")) {
        s.size_m = vec2(*size);
        if (!(s.size_m.x() > 0 && s.size_m.y() > 0 && s.size_m.maxCoeff() < 0.2))
          size->fail("[width, height], each within 0..0.2 m");
      }
      s.rgb = colour(l["color"]);
      spec.lamps.push_back(s);
    }
  }
  if (auto labels = root.find("labels")) spec.labels = labels_of(*labels);
  if (auto placards = root.find("placards")) {
    for (const ConfigNode& p : placards->elements()) {
      render::Placard placard;
      p.expect_keys({"name", "origin", "right", "up", "size", "labels"});
      placard.face = face_of(p);
      placard.name = p.get_string("name");
      if (placard.name.empty() || placard.name.size() > 64) p["name"].fail("1 to 64 characters");
      placard.size_m = vec2(p["size"]);
      if (!(placard.size_m.x() > 0 && placard.size_m.y() > 0 && placard.size_m.maxCoeff() < 2.0))
        p["size"].fail("[width, height], each within 0..2 m");
      placard.labels = labels_of(p["labels"]);
      // a label past the face's edge would float in the air beside it
      for (std::size_t i = 0; i < placard.labels.size(); ++i) {
        const render::LabelSpec& l = placard.labels[i];
        const double half_w = 0.5 * (static_cast<double>(l.text.size()) * 6 - 1) * l.height_m / 7;
        const Eigen::Vector2d reach = l.at_m.cwiseAbs() + Eigen::Vector2d(half_w, 0.5 * l.height_m);
        if ((reach - 0.5 * placard.size_m).maxCoeff() > 1e-9)
          p["labels"].at(i).fail("the label '" + l.text + "' reaches past the placard's size");
      }
      spec.placards.push_back(std::move(placard));
    }
  }
  return spec;
}

render::InstrumentsSpec load_instruments(const std::string& path) {
  return parse_instruments(ConfigNode::load_file(path));
}

}  // namespace vcockpit
