#include "tests/scenario/grasp_matrix/grasp_cells.hpp"

#include <cstdlib>
#include <stdexcept>
#include <string>

namespace vcockpit::test {

const std::vector<GraspCase>& grasp_objects() {
  static const std::vector<GraspCase> kObjects = {
      {"cup", "cup_pick_place.yaml", {0.36, -0.43, 0.75}},
      {"ball", "ball_pick_place.yaml", {0.58, -0.44, 0.73}},
      {"flashlight", "flashlight_pick_place.yaml", {0.565, -0.30, 0.718}},
      {"checklist", "checklist_pick_place.yaml", {0.31, -0.228, 0.704}},
  };
  return kObjects;
}

const std::map<std::string, std::string>& hand_sizes() {
  static const std::map<std::string, std::string> kSizes = {
      {"small", "hand_small.yaml"}, {"medium", "hand.yaml"}, {"large", "hand_large.yaml"}};
  return kSizes;
}

uint64_t grasp_matrix_seed() {
  const char* text = std::getenv("VCOCKPIT_GRASP_MATRIX_SEED");
  if (text == nullptr || *text == '\0') return kGraspMatrixSeed;
  char* end = nullptr;
  const unsigned long long seed = std::strtoull(text, &end, 10);
  if (*end != '\0') throw std::invalid_argument(std::string("VCOCKPIT_GRASP_MATRIX_SEED: not a number: ") + text);
  return seed;
}

const std::vector<Degradation>& degradations() {
  static const std::vector<Degradation> kDegradations = {
      {"clean", {}, {}},
      {"typical", {"typical"}, {}},                   // 60 Hz, jitter, glove noise, 1 % dropouts
      {"harsh", {"harsh"}, {}},                       // 30 Hz, all of it, grips in 0.25 s
      {"30hz", {"30hz"}, {}},
      {"120hz", {"120hz"}, {}},
      {"jitter", {"120hz", "jitter"}, {}},            // a 120 Hz tracker's jitter
      {"glove_noise", {"100hz", "glove_noise"}, {}},  // a 100 Hz glove's noise and 8 bits
      {"overrange", {"overrange"}, {}},
      {"dropouts", {"60hz", "dropouts"}, {}},
      {"gaps", {"gaps"}, {2.4, 4.8}},
      {"grip500ms", {"grip500ms"}, {}},
      {"grip250ms", {"grip250ms"}, {}},
  };
  return kDegradations;
}

degrade::DegradeSpec degradation_spec(const std::string& name) {
  for (const auto& d : degradations()) {
    if (d.name != name) continue;
    degrade::DegradeSpec spec;
    for (const auto& preset : d.presets) degrade::apply_preset(preset, spec);
    if (!d.gap_at_s.empty()) spec.gaps.at_s = d.gap_at_s;
    spec.seed = grasp_matrix_seed();
    return spec;
  }
  throw std::invalid_argument("no degradation " + name);
}

std::vector<Cell> grasp_cells() {
  std::vector<Cell> out;
  for (const auto& o : grasp_objects()) {
    for (const auto& [size, file] : hand_sizes()) {
      for (const char* d : {"clean", "typical", "harsh"}) out.push_back({o.object, size, d});
    }
    for (const auto& d : degradations()) {
      if (d.name != "clean" && d.name != "typical" && d.name != "harsh") {
        out.push_back({o.object, "medium", d.name});
      }
    }
  }
  return out;
}

Cell find_cell(const std::string& name) {
  for (const Cell& c : grasp_cells()) {
    if (c.name() == name) return c;
  }
  throw std::invalid_argument("no grasp matrix cell " + name);
}

const GraspCase& grasp_case(const std::string& object) {
  for (const auto& o : grasp_objects()) {
    if (o.object == object) return o;
  }
  throw std::invalid_argument("no grasp matrix object " + object);
}

}  // namespace vcockpit::test
