#include "image_generator/node/instrument_values.hpp"

#include <cmath>

namespace vcockpit::image_generator {

void InstrumentValues::on_info(const cockpit::SystemsInfo& info) {
  index_.assign(names_.size(), -1);
  unknown_.clear();
  for (std::size_t n = 0; n < names_.size(); ++n) {
    for (std::size_t i = 0; i < info.systems().size(); ++i)
      if (info.systems()[i].name().to_string() == names_[n]) index_[n] = static_cast<int>(i);
    if (index_[n] < 0) unknown_.push_back(names_[n]);
  }
  values_.assign(names_.size(), std::nan(""));
}

void InstrumentValues::on_state(const cockpit::SystemsState& state) {
  for (std::size_t n = 0; n < index_.size(); ++n) {
    const int i = index_[n];
    values_[n] = i >= 0 && static_cast<std::size_t>(i) < state.values().size()
                     ? state.values()[static_cast<std::size_t>(i)]
                     : std::nan("");
  }
}

}  // namespace vcockpit::image_generator
