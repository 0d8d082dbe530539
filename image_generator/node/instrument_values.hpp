#pragma once
// The instruments' values from the aircraft's systems: cockpit/systems_info says which index
// each system has, cockpit/systems_state the values. Names the instruments use that the systems
// node does not have are logged once (the instrument stays at rest).

#include <string>
#include <vector>

#include "idl/topics/systems_topics.hpp"
#include "image_generator/render/instrument_panel.hpp"

namespace vcockpit::image_generator {

class InstrumentValues {
 public:
  explicit InstrumentValues(const render::InstrumentsSpec& spec) : names_(spec.systems()) {
    values_.assign(names_.size(), std::nan(""));
  }

  void on_info(const cockpit::SystemsInfo& info);
  void on_state(const cockpit::SystemsState& state);
  // In the spec's systems() order; NaN where not known.
  const std::vector<double>& values() const { return values_; }
  // The names the systems node did not have (after its info).
  const std::vector<std::string>& unknown() const { return unknown_; }

 private:
  std::vector<std::string> names_;
  std::vector<int> index_;  // per name: into systems_state's values, -1 unknown
  std::vector<double> values_;
  std::vector<std::string> unknown_;
};

}  // namespace vcockpit::image_generator
