#include "hand/input_counts.hpp"

#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>

namespace vcockpit::hand {

InputCounts& InputCounts::operator+=(const InputCounts& o) {
  accepted += o.accepted;
  rejected_nonfinite += o.rejected_nonfinite;
  rejected_out_of_range += o.rejected_out_of_range;
  rejected_stale += o.rejected_stale;
  clamped += o.clamped;
  missing_columns += o.missing_columns;
  intervals += o.intervals;
  intervals_interpolated += o.intervals_interpolated;
  gaps_bridged += o.gaps_bridged;
  gaps_not_bridged += o.gaps_not_bridged;
  intervals_late += o.intervals_late;
  longest_interval_ns = std::max(longest_interval_ns, o.longest_interval_ns);
  glove_lost += o.glove_lost;
  return *this;
}

std::string input_counts_text(const InputCounts& c) {
  char text[512];
  std::snprintf(
      text, sizeof text,
      "accepted %llu, rejected %llu (non-finite %llu, out of range %llu, stale %llu), "
      "clamped %llu, missing columns %llu, intervals %llu (interpolated %llu, gaps "
      "bridged %llu, not bridged %llu, late %llu), longest %.3f s, glove lost %llu",
      static_cast<unsigned long long>(c.accepted), static_cast<unsigned long long>(c.rejected()),
      static_cast<unsigned long long>(c.rejected_nonfinite),
      static_cast<unsigned long long>(c.rejected_out_of_range),
      static_cast<unsigned long long>(c.rejected_stale), static_cast<unsigned long long>(c.clamped),
      static_cast<unsigned long long>(c.missing_columns),
      static_cast<unsigned long long>(c.intervals),
      static_cast<unsigned long long>(c.intervals_interpolated),
      static_cast<unsigned long long>(c.gaps_bridged),
      static_cast<unsigned long long>(c.gaps_not_bridged),
      static_cast<unsigned long long>(c.intervals_late),
      static_cast<double>(c.longest_interval_ns) * 1e-9,
      static_cast<unsigned long long>(c.glove_lost));
  return text;
}

nlohmann::ordered_json input_counts_json(const InputCounts& c) {
  return {{"accepted", c.accepted},
          {"rejected", c.rejected()},
          {"rejected_nonfinite", c.rejected_nonfinite},
          {"rejected_out_of_range", c.rejected_out_of_range},
          {"rejected_stale", c.rejected_stale},
          {"clamped", c.clamped},
          {"missing_columns", c.missing_columns},
          {"intervals", c.intervals},
          {"intervals_interpolated", c.intervals_interpolated},
          {"gaps_bridged", c.gaps_bridged},
          {"gaps_not_bridged", c.gaps_not_bridged},
          {"intervals_late", c.intervals_late},
          {"longest_interval_s", static_cast<double>(c.longest_interval_ns) * 1e-9},
          {"glove_lost", c.glove_lost}};
}

}  // namespace vcockpit::hand
