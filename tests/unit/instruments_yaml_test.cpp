// config/instruments.yaml (image_generator --instruments): it loads, every system it draws is one
// of config/aircraft.yaml's, its face frame is the instrument panel's; bad files are refused with
// file, line and key; an instrument whose system the systems node lacks rests (NaN).

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <set>
#include <string>

#include "common/config_error.hpp"
#include "common/yaml_config.hpp"
#include "image_generator/node/instrument_values.hpp"
#include "image_generator/node/instruments_yaml.hpp"
#include "systems/config/systems_yaml.hpp"

namespace vcockpit {
namespace {

std::string source_dir() {
  const char* dir = std::getenv("VCOCKPIT_SOURCE_DIR");
  return dir != nullptr ? dir : ".";
}

TEST(InstrumentsYaml, TheBundledPanelDrawsTheDefaultAircraftsSystems) {
  const render::InstrumentsSpec spec = load_instruments(source_dir() + "/config/instruments.yaml");
  EXPECT_EQ(spec.gauges.size(), 4u);
  EXPECT_EQ(spec.headings.size(), 1u);
  EXPECT_EQ(spec.lamps.size(), 14u);
  EXPECT_EQ(spec.labels.size(), 26u);
  ASSERT_EQ(spec.placards.size(), 2u);  // the pedestal's top and side
  EXPECT_EQ(spec.placards[0].labels.size() + spec.placards[1].labels.size(), 8u);
  const systems::SystemsModel aircraft = load_systems_model(source_dir() + "/config/aircraft.yaml");
  std::set<std::string> names;
  for (const systems::Element& e : aircraft.elements) names.insert(e.name);
  for (const std::string& s : spec.systems()) EXPECT_TRUE(names.count(s)) << s;
  // the face: the instrument panel's (its slab's face, tilted 15 deg back, facing the pilot)
  const Eigen::Vector3d normal = spec.face.X_GF.linear().col(2);
  EXPECT_NEAR(normal.x(), -std::cos(15 * M_PI / 180), 1e-5);
  EXPECT_NEAR(normal.z(), std::sin(15 * M_PI / 180), 1e-5);
}

std::string error_of(const std::string& yaml) {
  try {
    parse_instruments(ConfigNode::load_string(yaml, "instruments.yaml"));
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "loaded";
}

TEST(InstrumentsYaml, BadFilesNameTheLineAndKey) {
  const std::string panel = "panel: {origin: [0, 0, 1], right: [0, -1, 0], up: [0, 0, 1]}\n";
  EXPECT_EQ(error_of("panel: {origin: [0, 0, 1], right: [0, -1, 0], up: [0, 1, 0]}\n"),
            "instruments.yaml:1:8: panel: right and up must be unit vectors at right angles");
  EXPECT_EQ(error_of(panel + "gauges:\n  - {system: rpm, at: [0, 0], range: [10, 0]}\n"),
            "instruments.yaml:3:38: gauges[0].range: [min, max] with max > min");
  EXPECT_EQ(error_of(panel + "gauges:\n  - {system: rpm, at: [0, 0], range: [0, 1], radius: 2}\n"),
            "instruments.yaml:3:54: gauges[0].radius: must be within 0..1 m");
  EXPECT_EQ(error_of(panel + "lamps:\n  - {system: fire, at: [0, 0], color: [2, 0, 0]}\n"),
            "instruments.yaml:3:39: lamps[0].color: colour components are within 0..1");
  EXPECT_EQ(error_of(panel + "dials: []\n"),
            "instruments.yaml:2:1: dials: unknown key 'dials' (allowed: panel, gauges, headings, lamps, labels, placards)");
  EXPECT_EQ(error_of(panel + "labels:\n  - {text: \"\\u00e9t\u00e9\", at: [0, 0]}\n"),
            "instruments.yaml:3:12: labels[0].text: printable ASCII only (the panel font's)");
  // a placard: its own face, size and labels, each label on it
  const std::string placard =
      panel + "placards:\n  - {name: quadrant, origin: [0, 0, 0.7], right: [0, -1, 0], up: [1, 0, 0],"
              " size: [0.1, 0.05], labels: [";
  EXPECT_EQ(error_of(placard + "{text: FLAPS, at: [0.04, 0], height: 0.01}]}\n"),
            "instruments.yaml:3:105: placards[0].labels[0]: the label 'FLAPS' reaches past the "
            "placard's size");
  EXPECT_EQ(error_of(panel + "placards:\n  - {name: q, origin: [0, 0, 0.7], right: [0, -1, 0], "
                             "up: [0, 1, 0], size: [0.1, 0.1], labels: []}\n"),
            "instruments.yaml:3:5: placards[0]: right and up must be unit vectors at right angles");
  EXPECT_EQ(error_of(placard + "]}\n").find("size"), std::string::npos) << "a placard of no labels";
  const render::InstrumentsSpec spec = parse_instruments(ConfigNode::load_string(
      placard + "{text: UP, at: [0.01, 0.01], height: 0.01}]}\n", "instruments.yaml"));
  ASSERT_EQ(spec.placards.size(), 1u);
  EXPECT_EQ(spec.placards[0].name, "quadrant");
  ASSERT_EQ(spec.placards[0].labels.size(), 1u);
  EXPECT_TRUE(spec.placards[0].face.X_GF.linear().col(2).isApprox(Eigen::Vector3d::UnitZ()));
}

TEST(InstrumentValues, NamesAreBoundToTheSystemsInfoAndUnknownOnesRest) {
  render::InstrumentsSpec spec;
  spec.gauges.push_back({});
  spec.gauges.back().system = "rpm";
  spec.lamps.push_back({});
  spec.lamps.back().system = "no_such_light";
  image_generator::InstrumentValues values(spec);
  EXPECT_TRUE(std::isnan(values.values()[0]));
  cockpit::SystemsInfo info;
  for (const char* name : {"bus", "rpm"}) {
    cockpit::SystemInfo si;
    si.name(name);
    info.systems().push_back(si);
  }
  values.on_info(info);
  EXPECT_EQ(values.unknown(), std::vector<std::string>{"no_such_light"});
  cockpit::SystemsState state;
  state.values().push_back(1.0);
  state.values().push_back(61.5);
  values.on_state(state);
  EXPECT_EQ(values.values()[0], 61.5);
  EXPECT_TRUE(std::isnan(values.values()[1]));
}

}  // namespace
}  // namespace vcockpit
