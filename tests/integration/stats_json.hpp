#pragma once
// Reading the statistics files of physics_node --stats-out and dds_latency_floor --out in tests:
// top-level numbers and the p50/p99/max/count objects. Just enough JSON for the flat files those
// tools write (no escapes, no arrays); a missing key or a value that is not a number is NaN, so a
// check on it fails and names the key.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <string>

namespace vcockpit::test {

// The number after "key": in `text` (NaN if absent or not a number).
inline double json_number_at(const std::string& text, const std::string& key,
                             std::size_t from = 0) {
  const std::string tag = "\"" + key + "\": ";
  const auto at = text.find(tag, from);
  if (at == std::string::npos) return std::nan("");
  const char* start = text.c_str() + at + tag.size();
  char* end = nullptr;
  const double value = std::strtod(start, &end);
  return end == start ? std::nan("") : value;
}

// True if "key": appears at all (for keys a mode leaves out).
inline bool json_has(const std::string& text, const std::string& key) {
  return text.find("\"" + key + "\": ") != std::string::npos;
}

// The string after "key": (empty if absent).
inline std::string json_text(const std::string& text, const std::string& key) {
  const std::string tag = "\"" + key + "\": \"";
  const auto at = text.find(tag);
  if (at == std::string::npos) return "";
  const auto from = at + tag.size();
  return text.substr(from, text.find('"', from) - from);
}

struct LatencyFigures {
  double p50_us, p99_us, max_us, count;
};

// The {"p50":..,"p99":..,"max":..,"count":..} object named `key`.
inline LatencyFigures json_latency(const std::string& text, const std::string& key) {
  const auto at = text.find("\"" + key + "\": {");
  if (at == std::string::npos) {
    const double nan = std::nan("");
    return {nan, nan, nan, nan};
  }
  const auto end = text.find('}', at);
  const std::string object = text.substr(at, end == std::string::npos ? end : end - at + 1);
  return {json_number_at(object, "p50"), json_number_at(object, "p99"),
          json_number_at(object, "max"), json_number_at(object, "count")};
}

// p50 <= p99 <= max, all finite and positive: a distribution that was actually measured.
inline ::testing::AssertionResult plausible(const LatencyFigures& f) {
  const bool finite = std::isfinite(f.p50_us) && std::isfinite(f.p99_us) && std::isfinite(f.max_us);
  if (finite && f.p50_us > 0 && f.p50_us <= f.p99_us && f.p99_us <= f.max_us) {
    return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure() << "p50 " << f.p50_us << " us, p99 " << f.p99_us
                                       << " us, max " << f.max_us << " us";
}

}  // namespace vcockpit::test
