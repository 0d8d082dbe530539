// No NaN or infinity is written as JSON: remove_non_finite names and removes them, and json_text
// leaves them out and says where in the text itself (nlohmann alone writes null for them).

#include "common/json_file.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <limits>

namespace vcockpit {
namespace {

using Json = nlohmann::ordered_json;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

TEST(JsonFile, RemoveNonFiniteNamesEveryPlaceAndKeepsTheRest) {
  Json j;
  j["steps"] = 10;
  j["wall_s"] = kInf;
  j["final"]["cup"]["position"] = {0.1, kNaN, 0.3};
  j["final"]["cup"]["held_by"] = nullptr;
  j["final"]["ball"]["position"] = {0.1, 0.2, 0.3};
  j["stages"] = Json::array({Json{{"name", "broadphase"}, {"mean_us", -kInf}}, Json{{"mean_us", 2.0}}});
  j["mixed"] = Json::array({"a", kNaN, 3});
  const std::vector<std::string> removed = remove_non_finite(j);
  EXPECT_EQ(removed, (std::vector<std::string>{"wall_s", "final.cup.position",
                                               "stages[0].mean_us", "mixed[1]"}));
  EXPECT_FALSE(j.contains("wall_s"));
  EXPECT_FALSE(j["final"]["cup"].contains("position"));
  EXPECT_TRUE(j["final"]["cup"].contains("held_by"));
  EXPECT_EQ(j["final"]["ball"]["position"], Json({0.1, 0.2, 0.3}));
  EXPECT_EQ(j["stages"][0], Json({{"name", "broadphase"}}));
  EXPECT_EQ(j["stages"][1]["mean_us"], 2.0);
  EXPECT_EQ(j["mixed"], Json::array({"a", nullptr, 3}));
  EXPECT_EQ(j["steps"], 10);
}

TEST(JsonFile, TextNeverHoldsANonFiniteNumber) {
  Json j;
  j["t_s"] = 1.5;
  j["residual_force_N"] = kNaN;
  const std::string text = json_text(j);
  EXPECT_EQ(text, R"({"t_s":1.5,"non_finite_removed":["residual_force_N"]})");
  EXPECT_EQ(json_text(Json{{"a", 1.0}}), R"({"a":1.0})") << "finite values as they are";
  EXPECT_EQ(json_text(Json(kInf)), "null");
  EXPECT_TRUE(std::isnan(j["residual_force_N"].get<double>())) << "the caller's value untouched";
}

}  // namespace
}  // namespace vcockpit
