// The bundled control logs (config/glove_logs/panel_switches.csv, panel_knobs.csv,
// pedestal_levers.csv, and two_hand_controls_{right,left}.csv for both hands at once: recordings
// of the gestures in config/gestures/) through the offline runner
// on the default cockpit: each gives exactly its control events, in order — which control, from
// and to which position, the cause and the hand link — and nothing else: no loose object is
// touched or moved, and every control the log does not operate stays where it was. A change
// repeated by chatter at a threshold would be an extra event and fails the comparison; so would a
// missed one. (tests/integration/physics_node_test replays the same logs over DDS in lockstep
// and compares the files byte for byte.) Each control's body is on its joint in the contact solve.

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "physics_node/config/scene_config.hpp"
#include "physics_node/io/offline_runner.hpp"
#include "tests/support/monitor_log.hpp"
#include "tests/support/process.hpp"
#include "tests/support/test_files.hpp"

namespace vcockpit::test {
namespace {

struct Change {
  Change(std::string control_, std::string from_, std::string to_, std::string cause_,
         std::string link_, std::string hand_ = "")
      : control(std::move(control_)), from(std::move(from_)), to(std::move(to_)),
        cause(std::move(cause_)), link(std::move(link_)), hand(std::move(hand_)) {}
  std::string control, from, to, cause, link;  // link "" when the event names none
  std::string hand;  // "right" or "left"; "" when the expectation does not say
};

std::string text_of(const Change& c, bool with_hand) {
  return c.control + " " + c.from + "->" + c.to + " (" + c.cause + (c.link.empty() ? "" : " by " + c.link) +
         (with_hand && !c.hand.empty() ? ", " + c.hand + " hand" : "") + ")";
}

struct LogRun {
  std::vector<Change> changes;
  std::vector<std::string> grasped;  // objects grasped or released, in order
  std::string dir;
};

// One log per hand (each log's '# hand:' line says whose).
LogRun run_logs(const std::vector<std::string>& names) {
  physics_io::OfflineOptions options;
  options.scene_path = source_dir() + "/config/cockpit.yaml";
  for (const std::string& name : names)
    options.log_paths.push_back(source_dir() + "/config/glove_logs/" + name + ".csv");
  options.out_dir = make_temp_dir("control_logs_" + names.front());
  physics_io::run_offline(load_scene(options.scene_path), options);
  LogRun run;
  run.dir = options.out_dir;
  std::ifstream in(options.out_dir + "/events.jsonl");
  for (std::string line; std::getline(in, line);) {
    const auto j = nlohmann::json::parse(line);
    if (j.at("event") == "control") {
      run.changes.push_back({j.at("control"), j.at("from"), j.at("to"), j.at("cause"),
                             j.at("link").is_null() ? "" : j.at("link").get<std::string>(),
                             j.at("hand").is_null() ? "" : j.at("hand").get<std::string>()});
    } else {
      run.grasped.push_back(j.at("event").get<std::string>() + " " + j.at("object").get<std::string>());
    }
  }
  return run;
}

// The controls the log operates and the events it must give; every other control and every
// loose object must end where it started.
void expect_logs(const std::vector<std::string>& names,
                 const std::vector<Change>& expected, const std::vector<std::string>& expected_grasps,
                 bool with_hands = false) {
  const std::string name = names.front();
  const LogRun run = run_logs(names);
  std::string got, want;
  for (const auto& c : run.changes) got += text_of(c, with_hands) + "\n";
  for (const auto& c : expected) want += text_of(c, with_hands) + "\n";
  EXPECT_EQ(got, want) << name;
  std::string grasps, want_grasps;
  for (const auto& g : run.grasped) grasps += g + "\n";
  for (const auto& g : expected_grasps) want_grasps += g + "\n";
  EXPECT_EQ(grasps, want_grasps) << name;

  const physics::Scene scene = load_scene(source_dir() + "/config/cockpit.yaml");
  std::set<std::string> operated;
  for (const auto& c : expected) operated.insert(c.control);
  for (const auto& g : expected_grasps) operated.insert(g.substr(g.find(' ') + 1));
  for (const auto& [object, p] : read_final_poses(run.dir + "/summary.json")) {
    if (operated.count(object) != 0) continue;
    const int id = scene.find_object(object);
    ASSERT_GE(id, 0) << object;
    const Eigen::Vector3d start = scene.objects[static_cast<std::size_t>(id)].X_GO.translation();
    EXPECT_LT((p - start).norm(), 1e-3) << name << ": " << object << " moved";
  }
}

void expect_log(const std::string& name, const std::vector<Change>& expected,
                const std::vector<std::string>& expected_grasps) {
  expect_logs({name}, expected, expected_grasps);
}

const char* kIndexTip = "index_distal";

TEST(ControlLogs, PanelSwitchesPressFlipAndLiftEachSwitchOnce) {
  expect_log("panel_switches",
             {{"master_caution", "out", "pressed", "pushed", kIndexTip},
              {"master_caution", "pressed", "out", "mechanism", ""},
              {"avionics_master", "off", "on", "pushed", kIndexTip},
              {"avionics_master", "on", "off", "pushed", kIndexTip},
              {"landing_lights", "off", "taxi", "pushed", kIndexTip},
              {"landing_lights", "taxi", "on", "pushed", kIndexTip},
              {"landing_lights", "on", "taxi", "pushed", kIndexTip},
              {"landing_lights", "taxi", "off", "pushed", kIndexTip},
              {"fuel_pump", "off", "on", "pushed", kIndexTip},
              {"fuel_pump", "on", "off", "pushed", kIndexTip},
              {"engine_start_guard", "closed", "open", "pushed", kIndexTip},
              {"engine_start", "off", "start", "pushed", kIndexTip},
              {"engine_start", "start", "off", "mechanism", ""},
              {"engine_start_guard", "open", "closed", "pushed", kIndexTip},
              {"gear", "down", "up", "pushed", kIndexTip},
              {"gear", "up", "down", "pushed", kIndexTip}},
             {});
}

TEST(ControlLogs, PanelKnobsTurnTheSelectorTwoDetentsAndTheHeadingKnobTenClicks) {
  std::vector<Change> expected = {{"nav_mode", "off", "vor", "grasped", ""},
                                  {"nav_mode", "vor", "gps", "grasped", ""}};
  for (int twist = 0; twist < 2; ++twist) {
    for (int click = 0; click < 5; ++click) {
      expected.push_back({"heading_bug", "click", "between", "grasped", ""});
      expected.push_back({"heading_bug", "between", "click", "grasped", ""});
    }
  }
  expect_log("panel_knobs", expected,
             {"grasp nav_mode", "release nav_mode", "grasp heading_bug", "release heading_bug",
              "grasp heading_bug", "release heading_bug"});
}

// The throttle: lifted over its gate back to cutoff and forward again, on to full, back unlifted
// (the gate stops it at idle); the flaps: stopped by the gate at approach both ways, lifted over
// it. Both grasped by the power grip of config/gestures/pedestal_levers.yaml.
TEST(ControlLogs, PedestalLeversPassTheirGatesOnlyWhenLifted) {
  expect_log("pedestal_levers",
             {{"throttle", "idle", "cutoff", "grasped", ""},
              {"throttle", "cutoff", "idle", "grasped", ""},
              {"throttle", "idle", "full", "grasped", ""},
              {"throttle", "full", "idle", "grasped", ""},
              {"flaps", "up", "approach", "grasped", ""},
              {"flaps", "approach", "landing", "grasped", ""},
              {"flaps", "landing", "approach", "grasped", ""},
              {"flaps", "approach", "up", "grasped", ""}},
             {"grasp throttle", "release throttle", "grasp flaps", "release flaps"});
}

// Two hands at once (config/glove_logs/two_hand_controls_{right,left}.csv): the left hand works
// the throttle through its gate while the right hand's index fingertip flips the fuel pump on.
// Each change names its hand; nothing else moves.
TEST(ControlLogs, TheLeftHandWorksTheThrottleWhileTheRightFlipsTheFuelPump) {
  expect_logs({"two_hand_controls_right", "two_hand_controls_left"},
              {{"throttle", "idle", "cutoff", "grasped", "", "left"},
               {"fuel_pump", "off", "on", "pushed", kIndexTip, "right"},
               {"throttle", "cutoff", "idle", "grasped", "", "left"},
               {"throttle", "idle", "full", "grasped", "", "left"},
               {"throttle", "full", "idle", "grasped", "", "left"}},
              {"grasp throttle", "release throttle"}, /*with_hands=*/true);
}

}  // namespace
}  // namespace vcockpit::test
