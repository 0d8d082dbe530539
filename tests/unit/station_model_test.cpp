// The instructor station's model (instructor/station_model.hpp): what the page reads. Node
// status goes stale after 3 s; the sim time is the newest seen and stands still with the world;
// the physics node's acknowledgement says whether time is frozen and names saved checkpoints;
// events are numbered, named (objects, controls, positions) and read from a cursor; controls
// come with their positions; the pilot's view is the newest picture.

#include "instructor/station_model.hpp"

#include <gtest/gtest.h>

#include <string>

namespace vcockpit::instructor {
namespace {

constexpr int64_t kSecond = 1'000'000'000;

cockpit::NodeStatus status(const std::string& name) {
  cockpit::NodeStatus s;
  s.node_name(name);
  s.state(cockpit::RUNNING);
  s.detail("tracking");
  s.loop_rate_hz(1000.0);
  return s;
}

TEST(StationModel, NodesAreAliveUntilThreeSecondsWithoutStatus) {
  StationModel model;
  model.on_status(status("physics_node"), 10 * kSecond);
  auto nodes = model.state_json(12 * kSecond)["nodes"];
  ASSERT_EQ(nodes.size(), 1u);
  EXPECT_EQ(nodes[0]["name"], "physics_node");
  EXPECT_TRUE(nodes[0]["alive"].get<bool>());
  EXPECT_DOUBLE_EQ(nodes[0]["age_s"].get<double>(), 2.0);
  nodes = model.state_json(13 * kSecond + 1)["nodes"];
  EXPECT_FALSE(nodes[0]["alive"].get<bool>()) << "stale";
}

TEST(StationModel, SimTimeIsTheNewestSeenAndFrozenComesFromThePhysicsAck) {
  StationModel model;
  EXPECT_TRUE(model.state_json(0)["sim"]["sim_time_s"].is_null()) << "nothing seen yet";
  cockpit::HandState hand;
  hand.hand_id(0);
  hand.sim_time_ns(2 * kSecond);
  hand.tracking(true);
  hand.grasped_object_id(-1);
  model.on_hand(hand);
  cockpit::ObjectState older;
  older.sim_time_ns(kSecond);  // a late state of an object that stopped moving
  model.on_object_state(older);
  EXPECT_DOUBLE_EQ(model.state_json(0)["sim"]["sim_time_s"].get<double>(), 2.0);

  cockpit::SimAck ack;
  ack.command_seq(4);
  ack.command_source("instructor_station");
  ack.kind(cockpit::FREEZE);
  ack.node_name("physics_node");
  ack.accepted(true);
  ack.detail("frozen at 2.000 s");
  ack.sim_time_ns(2 * kSecond);
  ack.frozen(true);
  model.on_ack(ack);
  const auto sim = model.state_json(0)["sim"];
  EXPECT_TRUE(sim["frozen"].get<bool>());
  EXPECT_EQ(sim["last_ack"]["seq"], 4);
  EXPECT_EQ(sim["last_ack"]["command"], "freeze");
  EXPECT_EQ(sim["last_ack"]["detail"], "frozen at 2.000 s");

  // a glove driver's acknowledgement (no world time) changes nothing about the world
  ack.kind(cockpit::RESTART_REPLAY);
  ack.node_name("glove_driver");
  ack.sim_time_ns(-1);
  ack.frozen(false);
  model.on_ack(ack);
  EXPECT_TRUE(model.state_json(0)["sim"]["frozen"].get<bool>());
  // nor the systems node's answer to a reset: it has the world's time but does not know whether
  // the physics is frozen (it says false), and may arrive after the physics node's
  ack.kind(cockpit::RESET_TO_START);
  ack.node_name("systems_node");
  ack.sim_time_ns(2 * kSecond);
  ack.frozen(false);
  model.on_ack(ack);
  EXPECT_TRUE(model.state_json(0)["sim"]["frozen"].get<bool>());

  ack.kind(cockpit::SAVE_CHECKPOINT);
  ack.node_name("physics_node");
  ack.detail("checkpoint 'before taxi' saved at 2.000 s");
  ack.sim_time_ns(2 * kSecond);
  ack.frozen(true);
  model.on_ack(ack);
  model.on_ack(ack);  // saved over: named once
  EXPECT_EQ(model.state_json(0)["sim"]["checkpoints"], nlohmann::json({"before taxi"}));
}

TEST(StationModel, ControlsComeWithTheirPositionsAndEventsNameThem) {
  StationModel model;
  cockpit::ControlInfo info;
  info.control_id(2);
  info.name("landing_lights");
  info.kind(cockpit::TOGGLE);
  info.position_count(3);
  info.position_names("off|taxi|on|");
  model.on_control_info(info);
  cockpit::ControlState state;
  state.control_id(2);
  state.position(1);
  state.coordinate(0.0);
  state.held_by_hand_id(-1);
  model.on_control_state(state);
  const auto controls = model.state_json(0)["controls"];
  ASSERT_EQ(controls.size(), 1u);
  EXPECT_EQ(controls[0]["positions"], nlohmann::json({"off", "taxi", "on"}));
  EXPECT_EQ(controls[0]["position_name"], "taxi");
  EXPECT_EQ(controls[0]["kind"], "TOGGLE");
  EXPECT_TRUE(model.has_control_position(2, 2));
  EXPECT_FALSE(model.has_control_position(2, 3));
  EXPECT_FALSE(model.has_control_position(7, 0));

  cockpit::ControlEvent event;
  event.control_id(2);
  event.from_position(1);
  event.to_position(2);
  event.cause(cockpit::PUSHED);
  event.hand_id(1);
  event.sim_time_ns(3 * kSecond);
  model.on_control_event(event);
  cockpit::ObjectInfo cup;
  cup.object_id(5);
  cup.name("cup");
  model.on_object_info(cup);
  cockpit::GraspEvent grasp;
  grasp.object_id(5);
  grasp.hand_id(0);
  grasp.kind(cockpit::GRASP);
  grasp.reason("stable grasp: 3 links");
  model.on_grasp_event(grasp);
  const auto events = model.events_json(-1);
  ASSERT_EQ(events["events"].size(), 2u);
  EXPECT_EQ(events["events"][0]["text"], "CONTROL landing_lights taxi -> on (pushed, left hand)");
  EXPECT_EQ(events["events"][0]["kind"], "control");
  EXPECT_DOUBLE_EQ(events["events"][0]["sim_time_s"].get<double>(), 3.0);
  EXPECT_EQ(events["events"][1]["text"], "GRASP cup (right hand): stable grasp: 3 links");
  EXPECT_EQ(events["next"], 2);
}

// The topics are independent: an event can come before its control's or object's info. It is
// named when read, so the info that comes after it still names it.
TEST(StationModel, AnEventThatComesBeforeItsInfoIsNamedWhenRead) {
  StationModel model;
  cockpit::ControlEvent event;
  event.control_id(4);
  event.from_position(0);
  event.to_position(1);
  event.cause(cockpit::PUSHED);
  event.hand_id(0);
  event.sim_time_ns(2 * kSecond);
  model.on_control_event(event);
  cockpit::GraspEvent grasp;
  grasp.object_id(9);
  grasp.hand_id(1);
  grasp.kind(cockpit::RELEASE);
  grasp.reason("hand opened");
  model.on_grasp_event(grasp);
  auto events = model.events_json(-1)["events"];
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[0]["text"], "CONTROL control 4 0 -> 1 (pushed, right hand)") << "not known yet";
  EXPECT_EQ(events[1]["text"], "RELEASE object 9 (left hand): hand opened");

  cockpit::ControlInfo info;
  info.control_id(4);
  info.name("flaps");
  info.kind(cockpit::LEVER);
  info.position_count(2);
  info.position_names("up|approach|");
  model.on_control_info(info);
  cockpit::ObjectInfo torch;
  torch.object_id(9);
  torch.name("flashlight");
  model.on_object_info(torch);
  events = model.events_json(-1)["events"];
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[0]["text"], "CONTROL flaps up -> approach (pushed, right hand)");
  EXPECT_EQ(events[1]["text"], "RELEASE flashlight (left hand): hand opened");
}

TEST(StationModel, EventsAreReadFromACursorAndTheOldestGoFirst) {
  StationModel model;
  for (int i = 0; i < 250; ++i) model.on_command_sent("SENT freeze (#" + std::to_string(i) + ")");
  auto reply = model.events_json(-1);
  ASSERT_EQ(reply["events"].size(), StationModel::kEventsPerReply) << "the newest, at most 200";
  EXPECT_EQ(reply["events"].front()["seq"], 50);
  EXPECT_EQ(reply["next"], 250);
  reply = model.events_json(247);
  ASSERT_EQ(reply["events"].size(), 2u);
  EXPECT_EQ(reply["events"][0]["seq"], 248);
  reply = model.events_json(249);
  EXPECT_TRUE(reply["events"].empty());
  EXPECT_EQ(reply["next"], 250);
  reply = model.events_json(5000);  // a cursor from a station that restarted since
  EXPECT_TRUE(reply["events"].empty());
  for (std::size_t i = 0; i < StationModel::kMaxEvents; ++i) model.on_command_sent("more");
  reply = model.events_json(0);
  EXPECT_EQ(reply["events"].front()["seq"], 250) << "only the last kMaxEvents are kept";
}

TEST(StationModel, TheViewIsTheNewestPicture) {
  StationModel model;
  std::string png;
  EXPECT_FALSE(model.view_png(png));
  EXPECT_TRUE(model.state_json(0)["view"].is_null());
  cockpit::PreviewFrame frame;
  frame.frame_seq(41);
  frame.sim_time_ns(kSecond / 2);
  frame.width_px(640);
  frame.height_px(360);
  frame.png({0x89, 'P', 'N', 'G'});
  model.on_preview(frame, 5 * kSecond);
  ASSERT_TRUE(model.view_png(png));
  EXPECT_EQ(png, std::string("\x89PNG"));
  const auto view = model.state_json(6 * kSecond)["view"];
  EXPECT_EQ(view["frame_seq"], 41);
  EXPECT_DOUBLE_EQ(view["age_s"].get<double>(), 1.0);
  EXPECT_EQ(view["width_px"], 640);
}

// The aircraft (systems_node): each system's value, a machine's with its state's name; the
// failures and whether each is inserted; the lesson's procedures as their scores say; failure
// changes and acknowledgements as events.
TEST(StationModel, SystemsFailuresAndTheLessonsScoreAreShown) {
  StationModel model;
  EXPECT_FALSE(model.knows_failures());
  EXPECT_TRUE(model.state_json(0)["systems"].is_null());
  cockpit::SystemsInfo info;
  cockpit::SystemInfo rpm;
  rpm.name("rpm");
  rpm.kind(cockpit::SYSTEM_LAG);
  rpm.unit("%");
  cockpit::SystemInfo engine;
  engine.name("engine");
  engine.kind(cockpit::SYSTEM_MACHINE);
  engine.state_names("stopped|cranking|running|");
  info.systems().push_back(rpm);
  info.systems().push_back(engine);
  cockpit::FailureInfo fire;
  fire.name("engine_fire");
  fire.text("Engine fire");
  info.failures().push_back(fire);
  model.on_systems_info(info);
  cockpit::SystemsState state;
  state.sim_time_ns(2 * kSecond);
  state.values().push_back(22.5);
  state.values().push_back(1.0);
  state.failures().push_back(true);
  model.on_systems_state(state);
  EXPECT_TRUE(model.knows_failures());
  EXPECT_TRUE(model.has_failure("engine_fire"));
  EXPECT_FALSE(model.has_failure("fire"));
  auto j = model.state_json(0);
  EXPECT_DOUBLE_EQ(j["systems"]["sim_time_s"].get<double>(), 2.0);
  EXPECT_DOUBLE_EQ(j["systems"]["values"]["rpm"]["value"].get<double>(), 22.5);
  EXPECT_EQ(j["systems"]["values"]["rpm"]["unit"], "%");
  EXPECT_EQ(j["systems"]["values"]["engine"]["state"], "cranking");
  ASSERT_EQ(j["failures"].size(), 1u);
  EXPECT_EQ(j["failures"][0]["inserted"], true);

  cockpit::SystemsEvent cleared;
  cleared.kind(cockpit::FAILURE_CLEARED);
  cleared.name("engine_fire");
  cleared.sim_time_ns(3 * kSecond);
  model.on_systems_event(cleared);
  EXPECT_EQ(model.state_json(0)["failures"][0]["inserted"], false);
  cockpit::FailureAck ack;
  ack.failure("engine_fire");
  ack.accepted(true);
  ack.detail("inserted");
  ack.command_seq(4);
  ack.command_source("instructor_station");
  model.on_failure_ack(ack);
  const auto events = model.events_json(-1)["events"];
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[0]["text"], "FAILURE engine_fire cleared");
  EXPECT_EQ(events[1]["text"], "FAILURE engine_fire: inserted (#4 from instructor_station)");

  cockpit::ProcedureScore score;
  score.index(1);
  score.count(2);
  score.lesson("Start and land");
  score.name("engine_start");
  score.title("Engine start");
  score.state(cockpit::PROCEDURE_RUNNING);
  score.started_time_ns(6 * kSecond);
  score.ended_time_ns(-1);
  score.errors(1);
  cockpit::ProcedureStepScore step;
  step.item("Start guard");
  step.action("OPEN");
  step.status(cockpit::STEP_DONE);
  step.out_of_order(true);
  step.done_time_ns(6 * kSecond);
  step.since_previous_ns(0);
  score.steps().push_back(step);
  model.on_procedure_score(score);
  j = model.state_json(0)["procedures"];
  EXPECT_EQ(j["lesson"], "Start and land");
  ASSERT_EQ(j["list"].size(), 1u);
  EXPECT_EQ(j["list"][0]["state"], "running");
  EXPECT_EQ(j["list"][0]["errors"], 1);
  EXPECT_TRUE(j["list"][0]["ended_s"].is_null());
  EXPECT_EQ(j["list"][0]["steps"][0]["status"], "done");
  EXPECT_EQ(j["list"][0]["steps"][0]["out_of_order"], true);
  // another lesson of one procedure: the second is dropped
  score.count(1);
  score.index(0);
  model.on_procedure_score(score);
  EXPECT_EQ(model.state_json(0)["procedures"]["list"].size(), 1u);
}

}  // namespace
}  // namespace vcockpit::instructor
