// The bundled procedure logs (config/glove_logs/procedures_right.csv, procedures_errors_right.csv:
// recordings of config/gestures/procedures_*.yaml) flown in the default cockpit by the offline
// runner, then the default aircraft and lesson (config/aircraft.yaml, config/lessons/default.yaml)
// stepped on its control frames: each gives exactly its control events and its expected score,
// tests/data/procedures/*.json, byte for byte. The flow done right scores its three procedures
// complete with no error and leaves the gear-unsafe abnormal waiting; with the failure inserted
// at 50 s the abnormal is flown and complete too; the other log flies the flaps before the gear
// (out of order) and never switches the landing lights on (missed). (systems_node_test runs the
// same in a lockstep rig and compares the files.)

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <string>
#include <vector>

#include "physics_node/config/scene_config.hpp"
#include "physics_node/io/offline_runner.hpp"
#include "systems/config/procedure_yaml.hpp"
#include "systems/config/systems_yaml.hpp"
#include "systems/control_frames_file.hpp"
#include "systems/systems_session.hpp"
#include "tests/support/process.hpp"
#include "tests/support/test_files.hpp"

namespace vcockpit::test {
namespace {

struct Flown {
  std::vector<std::string> controls;  // "gear down->up", in order
  std::string score;                  // procedures.json
};

Flown fly(const std::string& log, const std::vector<std::string>& failures) {
  physics_io::OfflineOptions options;
  options.scene_path = source_dir() + "/config/cockpit.yaml";
  options.log_paths = {source_dir() + "/config/glove_logs/" + log + ".csv"};
  options.out_dir = make_temp_dir("procedures_" + log);
  physics_io::run_offline(load_scene(options.scene_path), options);
  Flown flown;
  std::ifstream events(options.out_dir + "/events.jsonl");
  for (std::string line; std::getline(events, line);) {
    const auto j = nlohmann::json::parse(line);
    if (j.at("event") == "control")
      flown.controls.push_back(j.at("control").get<std::string>() + " " +
                               j.at("from").get<std::string>() + "->" + j.at("to").get<std::string>());
  }
  const systems::ControlFrames frames = systems::read_control_frames(options.out_dir + "/control_frames.csv");
  systems::SessionOptions session_options;
  session_options.out_dir = options.out_dir + "/systems";
  session_options.lesson = load_lesson(source_dir() + "/config/lessons/default.yaml");
  for (const std::string& f : failures) session_options.failures.push_back(systems::parse_scheduled_failure(f));
  systems::SystemsSession session(load_systems_model(source_dir() + "/config/aircraft.yaml"),
                                  frames.controls, session_options);
  for (const systems::ControlFrame& f : frames.frames) session.take(f);
  session.finish();
  flown.score = read_text(session_options.out_dir + "/procedures.json");
  return flown;
}

const std::vector<std::string> kStartAndTakeOff = {
    "avionics_master off->on", "fuel_pump off->on", "engine_start_guard closed->open",
    "engine_start off->start", "engine_start start->off", "engine_start_guard open->closed",
    "gear down->up"};

std::vector<std::string> then(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

TEST(ProcedureLogs, TheFlowDoneRightScoresCompleteAndTheAbnormalWaits) {
  const Flown flown = fly("procedures_right", {});
  EXPECT_EQ(flown.controls,
            then(kStartAndTakeOff, {"gear up->down", "landing_lights off->taxi",
                                    "landing_lights taxi->on", "flaps up->approach",
                                    "flaps approach->landing", "master_caution out->pressed",
                                    "master_caution pressed->out", "gear down->up", "gear up->down"}));
  EXPECT_EQ(flown.score, read_text(source_dir() + "/tests/data/procedures/right.json"));
  const auto score = nlohmann::json::parse(flown.score);
  EXPECT_EQ(score.at("complete"), 3);
  EXPECT_EQ(score.at("errors"), 0);
  EXPECT_EQ(score.at("procedures").at(3).at("state"), "waiting");
}

TEST(ProcedureLogs, TheGearUnsafeAbnormalIsFlownAndComplete) {
  const Flown flown = fly("procedures_right", {"50:gear_unsafe_left"});
  EXPECT_EQ(flown.score, read_text(source_dir() + "/tests/data/procedures/right_gear_unsafe.json"));
  const auto score = nlohmann::json::parse(flown.score);
  EXPECT_EQ(score.at("complete"), 4);
  EXPECT_EQ(score.at("errors"), 0);
  const auto& abnormal = score.at("procedures").at(3);
  EXPECT_EQ(abnormal.at("started_s"), 50.0);
  EXPECT_EQ(abnormal.at("steps").at(3).at("since_previous_s"), 7.5);  // the right leg's transit
}

TEST(ProcedureLogs, TheFlapsBeforeTheGearAndNoLandingLightsAreScoredAsSuch) {
  const Flown flown = fly("procedures_errors_right", {});
  EXPECT_EQ(flown.controls, then(kStartAndTakeOff, {"flaps up->approach", "flaps approach->landing",
                                                    "gear up->down"}));
  EXPECT_EQ(flown.score, read_text(source_dir() + "/tests/data/procedures/errors.json"));
  const auto landing = nlohmann::json::parse(flown.score).at("procedures").at(2);
  EXPECT_EQ(landing.at("state"), "incomplete");
  EXPECT_EQ(landing.at("errors"), 2);
  EXPECT_EQ(landing.at("steps").at(2).at("out_of_order"), true);  // flaps
  EXPECT_EQ(landing.at("steps").at(3).at("status"), "missed");    // landing lights
}

}  // namespace
}  // namespace vcockpit::test
