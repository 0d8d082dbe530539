#include "hand/tracking/tracker_json.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>

namespace vcockpit::hand::tracking {

nlohmann::json read_json_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw JointsLogError(path + ": cannot open file");
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw JointsLogError(path + ": not JSON: " + e.what());
  }
}

void FrameErrors::fail(std::size_t frame, const std::string& what) const {
  throw JointsLogError(path_ + ": frame " + std::to_string(frame) + ": " + what);
}

double FrameErrors::number(const nlohmann::json& v, std::size_t frame, const std::string& field) const {
  if (!v.is_number()) fail(frame, "'" + field + "' is not a number");
  const double x = v.get<double>();
  if (!std::isfinite(x)) fail(frame, "'" + field + "' is not finite");
  return x;
}

}  // namespace vcockpit::hand::tracking
