#pragma once
// Reading the statistics files of physics_node --stats-out and dds_latency_floor --out in tests:
// top-level numbers and strings, and the p50/p99/max/count objects, parsed with nlohmann::json
// (spacing and number format do not matter). A file that does not parse, a missing key or a value
// that is not a number is NaN, so a check on it fails and names the key.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <string>

namespace vcockpit::test {

// The parsed text; a discarded value (no keys) if it is not JSON.
inline nlohmann::json parse_json(const std::string& text) {
  return nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
}

// The number under `key` in a JSON object (NaN if absent or not a number).
inline double json_number_in(const nlohmann::json& object, const std::string& key) {
  if (!object.is_object()) return std::nan("");
  const auto it = object.find(key);
  return it != object.end() && it->is_number() ? it->get<double>() : std::nan("");
}

// The top-level number "key" of `text` (NaN if absent or not a number).
inline double json_number_at(const std::string& text, const std::string& key) {
  return json_number_in(parse_json(text), key);
}

// True if the top-level "key" appears at all (for keys a mode leaves out).
inline bool json_has(const std::string& text, const std::string& key) {
  const auto j = parse_json(text);
  return j.is_object() && j.contains(key);
}

// The top-level string "key" (empty if absent or not a string).
inline std::string json_text(const std::string& text, const std::string& key) {
  const auto j = parse_json(text);
  if (!j.is_object()) return "";
  const auto it = j.find(key);
  return it != j.end() && it->is_string() ? it->get<std::string>() : "";
}

struct LatencyFigures {
  double p50_us, p99_us, max_us, count;
};

// The {"p50":..,"p99":..,"max":..,"count":..} object named `key`.
inline LatencyFigures json_latency(const std::string& text, const std::string& key) {
  const auto j = parse_json(text);
  const nlohmann::json object = j.is_object() && j.contains(key) ? j.at(key) : nlohmann::json();
  return {json_number_in(object, "p50"), json_number_in(object, "p99"),
          json_number_in(object, "max"), json_number_in(object, "count")};
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
