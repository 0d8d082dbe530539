// No NaN or infinity reaches the offline runner's files: a world driven into non-finite states
// writes three files that parse and hold only finite numbers, and each refusal is counted and
// named once in the log (non_finite_guard.hpp, run_outputs.hpp).

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <map>
#include <memory>
#include <sstream>

#include "physics_node/config/scene_config.hpp"
#include "physics_node/io/non_finite_guard.hpp"
#include "physics_node/io/offline_runner.hpp"
#include "physics_node/io/run_outputs.hpp"
#include "tests/support/test_files.hpp"

namespace vcockpit::test {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// The default logger writes into a string for the test's length.
class CapturedLog {
 public:
  CapturedLog() : previous_(spdlog::default_logger()) {
    auto sink = std::make_shared<spdlog::sinks::ostream_sink_mt>(text_);
    spdlog::set_default_logger(std::make_shared<spdlog::logger>("captured", sink));
  }
  ~CapturedLog() { spdlog::set_default_logger(previous_); }
  std::string text() const { return text_.str(); }
  // How many lines hold `part`.
  int lines_with(const std::string& part) const {
    std::istringstream in(text_.str());
    int n = 0;
    for (std::string line; std::getline(in, line);) n += line.find(part) != std::string::npos;
    return n;
  }

 private:
  std::ostringstream text_;
  std::shared_ptr<spdlog::logger> previous_;
};

// Every number in `j` is finite (and none is missing as null where a number should be).
void expect_all_finite(const nlohmann::json& j, const std::string& where) {
  if (j.is_number_float()) {
    EXPECT_TRUE(std::isfinite(j.get<double>())) << where;
  } else if (j.is_object()) {
    for (auto it = j.begin(); it != j.end(); ++it) expect_all_finite(*it, where + "." + it.key());
  } else if (j.is_array()) {
    for (std::size_t i = 0; i < j.size(); ++i)
      expect_all_finite(j[i], where + "[" + std::to_string(i) + "]");
  }
}

std::string printf_fixed(double v, int digits) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", digits, v);
  return text;
}

nlohmann::json parse_json(const std::string& text, const std::string& what) {
  nlohmann::json j;
  EXPECT_NO_THROW(j = nlohmann::json::parse(text)) << what << ": " << text;
  return j;
}

// The rows of trajectories.csv per object; every numeric field must parse whole and be finite.
std::map<std::string, int> check_trajectories(const std::string& path) {
  std::istringstream in(read_text(path));
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "t_s,object,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,held_by,control_q,control_position");
  std::map<std::string, int> rows;
  while (std::getline(in, line)) {
    std::vector<std::string> fields;
    std::istringstream row(line);
    for (std::string f; std::getline(row, f, ',');) fields.push_back(f);
    if (line.back() == ',') fields.push_back("");
    EXPECT_EQ(fields.size(), 18u) << line;
    if (fields.size() != 18u) continue;
    ++rows[fields[1]];
    for (std::size_t i = 0; i < 15; ++i) {
      if (i == 1) continue;
      char* end = nullptr;
      const double v = std::strtod(fields[i].c_str(), &end);
      EXPECT_TRUE(!fields[i].empty() && *end == '\0' && std::isfinite(v))
          << "field " << i << " '" << fields[i] << "' of: " << line;
    }
  }
  return rows;
}

TEST(RunOutputs, AWorldDrivenNonFiniteWritesOnlyFiniteNumbers) {
  // the default cockpit with three objects broken from the start: the ball spinning at NaN
  // rad/s, the flashlight flying at infinite speed, the cup at 1e300 m/s. The body check puts
  // each back after the first step; the row before it must not carry their states out.
  physics::Scene scene = load_scene(source_dir() + "/config/cockpit.yaml");
  const auto object = [&](const char* name) -> physics::ObjectSpec& {
    return scene.objects.at(static_cast<std::size_t>(scene.find_object(name)));
  };
  object("ball").w_G = Eigen::Vector3d(0.0, kNaN, 0.0);
  object("flashlight").v_G = Eigen::Vector3d(kInf, 0.0, 0.0);
  object("cup").v_G = Eigen::Vector3d(1e300, 0.0, 0.0);
  physics_io::OfflineOptions options;
  options.scene_path = "cockpit.yaml with broken objects";
  options.duration_s = 0.05;
  options.out_dir = make_temp_dir("run_outputs_test");
  CapturedLog log;
  const physics_io::RunSummary summary = physics_io::run_offline(scene, options);
  EXPECT_EQ(summary.non_finite_refused, 2u) << "the ball's and the flashlight's first rows";

  const std::map<std::string, int> rows = check_trajectories(options.out_dir + "/trajectories.csv");
  EXPECT_EQ(rows.at("cup"), 6) << "t = 0 and every 10 ms after";
  EXPECT_EQ(rows.at("ball"), 5) << "the row at t = 0 left out";
  EXPECT_EQ(rows.at("flashlight"), 5) << "the row at t = 0 left out";
  EXPECT_EQ(log.lines_with("trajectories.csv: refused a non-finite angular velocity of ball at "
                           "0.000 s"), 1)
      << log.text();
  EXPECT_EQ(log.lines_with("refused a non-finite linear velocity of flashlight"), 1) << log.text();

  std::istringstream events(read_text(options.out_dir + "/events.jsonl"));
  for (std::string line; std::getline(events, line);) expect_all_finite(parse_json(line, "event"), "event");
  const nlohmann::json s = parse_json(read_text(options.out_dir + "/summary.json"), "summary");
  expect_all_finite(s, "summary");
  EXPECT_EQ(s.at("non_finite_refused"), 2);
  for (const char* name : {"cup", "ball", "flashlight"})
    EXPECT_EQ(s.at("final").at(name).at("position").size(), 3u) << name << " put back, finite";
}

// A momentary button starts pressed and springs back out: the change is a control event, its
// coordinate and position are trajectory columns, its final position is in the summary.
TEST(RunOutputs, AControlsChangeIsAnEventAndItsCoordinateATrajectoryColumn) {
  physics::Scene scene;
  physics::ObjectSpec cap;
  cap.name = "reset";
  cap.dynamic = true;
  cap.shape = physics::Shape::box({0.008, 0.012, 0.012});
  cap.mass_kg = 0.005;
  cap.I_O = cap.shape.unit_density_inertia() * (cap.mass_kg / cap.shape.volume_m3());
  cap.control = 0;
  scene.objects.push_back(cap);
  physics::ControlSpec c;
  c.name = "reset";
  c.joint = physics::JointKind::kPrismatic;
  c.body = 0;
  c.q_max = 0.004;
  c.q_initial = 0.004;
  c.q_rest = -0.002;
  c.stiffness = 1500.0;
  c.damping = 2.7;
  c.positions = {{"out", 0.0, -1.0, 0.0015}, {"pressed", 0.004, 0.003, 1.0}};
  scene.controls.push_back(c);
  physics_io::OfflineOptions options;
  options.scene_path = "one button";
  options.duration_s = 0.05;
  options.out_dir = make_temp_dir("run_outputs_test");
  const physics_io::RunSummary summary = physics_io::run_offline(scene, options);
  EXPECT_EQ(summary.control_events, 1);

  std::istringstream events(read_text(options.out_dir + "/events.jsonl"));
  std::string line;
  ASSERT_TRUE(std::getline(events, line));
  const nlohmann::json e = parse_json(line, "event");
  EXPECT_EQ(e.at("event"), "control");
  EXPECT_EQ(e.at("control"), "reset");
  EXPECT_EQ(e.at("from"), "pressed");
  EXPECT_EQ(e.at("to"), "out");
  EXPECT_TRUE(e.at("hand").is_null());
  EXPECT_TRUE(e.at("link").is_null());
  EXPECT_EQ(e.at("cause"), "mechanism");
  EXPECT_GT(e.at("t_s").get<double>(), 0.0);
  EXPECT_FALSE(std::getline(events, line)) << "one event: " << line;

  std::istringstream rows(read_text(options.out_dir + "/trajectories.csv"));
  std::getline(rows, line);  // header
  ASSERT_TRUE(std::getline(rows, line));
  EXPECT_NE(line.find(",0.004000000,pressed"), std::string::npos) << "t = 0: " << line;
  std::string last = line;
  while (std::getline(rows, line)) last = line;
  EXPECT_NE(last.find(",0.000000000,out"), std::string::npos) << "the end: " << last;

  const nlohmann::json s = parse_json(read_text(options.out_dir + "/summary.json"), "summary");
  EXPECT_EQ(s.at("controls").at("reset"), "out");
  EXPECT_EQ(s.at("control_events"), 1);
}

// An object's row is the text of its state at that write: the writer reuses the text of an
// object that has not changed since its last row (most lie still), and must see a change of one
// bit -- here a velocity of 0.0 turned -0.0, which prints differently.
TEST(TrajectoryWriter, EachRowIsTheObjectsStateAtThatWriteEvenWhenOneBitChanged) {
  physics::Scene scene;
  physics::ObjectSpec floor;
  floor.name = "floor";
  floor.shape = physics::Shape::box({1.0, 1.0, 0.1});
  floor.X_GO.translation() = Eigen::Vector3d(0.0, 0.0, -0.05);
  scene.objects.push_back(floor);
  physics::ObjectSpec box = floor;
  box.name = "box";
  box.dynamic = true;
  box.shape = physics::Shape::box({0.04, 0.04, 0.04});
  box.mass_kg = 0.1;
  box.I_O = box.shape.unit_density_inertia() * (box.mass_kg / box.shape.volume_m3());
  box.X_GO.translation() = Eigen::Vector3d(0.0, 0.0, 0.1);  // falling
  scene.objects.push_back(box);
  physics::ObjectSpec still = box;
  still.name = "still";
  still.X_GO.translation() = Eigen::Vector3d(0.3, 0.0, 0.02);  // at rest on the floor
  scene.objects.push_back(still);
  physics::World world(scene);

  const auto expected_row = [&](int i) {
    const physics::BodyState& b = world.bodies()[static_cast<std::size_t>(i)];
    const Eigen::Vector3d p = b.X_GO.translation();
    const Eigen::Quaterniond q(b.X_GO.linear());
    std::string row = printf_fixed(static_cast<double>(world.time_ns()) / 1e9, 6) + "," +
                      scene.objects[static_cast<std::size_t>(i)].name;
    for (const double v : {p.x(), p.y(), p.z(), q.w(), q.x(), q.y(), q.z(), b.v_G.x(), b.v_G.y(),
                           b.v_G.z(), b.w_G.x(), b.w_G.y(), b.w_G.z()})
      row += "," + printf_fixed(v, 9);
    return row + ",,,\n";
  };
  const std::string path = make_temp_dir("trajectory_writer_test") + "/trajectories.csv";
  std::string expected = "t_s,object,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,held_by,control_q,control_position\n";
  {
    physics_io::TrajectoryWriter writer(path);
    const auto write = [&] {
      writer.write(world);
      expected += expected_row(1) + expected_row(2);
    };
    write();
    for (int step = 0; step < 30; ++step) {
      world.step();
      if (step % 3 == 2) write();
    }
    physics::WorldState state = world.state();
    state.bodies[2].v_G.x() = 0.0;
    world.restore(state);
    write();
    state.bodies[2].v_G.x() = -0.0;  // one bit
    world.restore(state);
    write();
    writer.commit();
  }
  EXPECT_EQ(read_text(path), expected);
}

TEST(RunOutputs, AnEventsNonFiniteResidualIsLeftOutAndNamed) {
  const std::string dir = make_temp_dir("run_outputs_test");
  physics_io::EventWriter writer(dir + "/events.jsonl");
  physics::GraspEvent e;
  e.grasp = true;
  e.object = 6;
  e.t_ns = 2'500'000'000;
  e.contacts = 3;
  e.residual_force_N = kNaN;
  e.residual_torque_Nm = 0.1;
  CapturedLog log;
  writer.write(e, "cup");
  writer.write(e, "cup");
  writer.commit();
  EXPECT_EQ(writer.grasps(), 2) << "the event itself is still written";
  EXPECT_EQ(writer.refused(), 2u);
  EXPECT_EQ(log.lines_with("events.jsonl: refused a non-finite residual_force_N of cup at 2.500 s"), 1)
      << "named once: " << log.text();
  std::istringstream lines(read_text(dir + "/events.jsonl"));
  int n = 0;
  for (std::string line; std::getline(lines, line); ++n) {
    const nlohmann::json j = parse_json(line, "event");
    expect_all_finite(j, "event");
    EXPECT_FALSE(j.contains("residual_force_N")) << line;
    EXPECT_EQ(j.at("residual_torque_Nm"), 0.1);
    EXPECT_FALSE(j.contains("non_finite_removed")) << "the writer's own refusal, not the net's";
  }
  EXPECT_EQ(n, 2);
}

TEST(RunOutputs, ASummaryWithNonFiniteFiguresParsesAndCountsThem) {
  physics::Scene scene = load_scene(source_dir() + "/config/cockpit.yaml");
  physics::World world(scene);
  physics_io::RunSummary s;
  s.steps = 10;
  s.wall_s = 0.0;
  s.simulated_s = 0.01;
  s.penetration_max_m = kInf;
  s.stage_total_s.assign(physics::kStageCount, 0.0);
  s.stage_total_s[static_cast<int>(physics::Stage::kNarrowphase)] = kNaN;
  s.non_finite_refused = 5;  // from the other two files
  const std::string path = make_temp_dir("run_outputs_test") + "/summary.json";
  CapturedLog log;
  physics_io::write_summary(path, s, world);
  const nlohmann::json j = parse_json(read_text(path), "summary");
  expect_all_finite(j, "summary");
  EXPECT_FALSE(j.contains("hand_penetration_max_m"));
  EXPECT_FALSE(j.at("stage_wall_s").contains("narrowphase"));
  EXPECT_EQ(j.at("non_finite_refused"), 7);
  EXPECT_EQ(log.lines_with("summary.json: refused a non-finite stage_wall_s.narrowphase"), 1)
      << log.text();
}

TEST(NonFiniteGuard, CountsEveryRefusalAndNamesEachSubjectsFieldOnce) {
  physics_io::NonFiniteGuard guard("cockpit/object_state");
  CapturedLog log;
  EXPECT_TRUE(guard.pass(true, "cup", "pose", 0));
  EXPECT_FALSE(guard.pass(false, "cup", "pose", 1'000'000));
  EXPECT_FALSE(guard.pass(false, "cup", "pose", 2'000'000));
  EXPECT_FALSE(guard.pass(false, "cup", "angular velocity", 3'000'000));
  EXPECT_FALSE(guard.pass(false, "ball", "pose", 4'000'000));
  EXPECT_EQ(guard.refused(), 4u);
  EXPECT_EQ(log.lines_with("refused a non-finite"), 3) << log.text();
  EXPECT_EQ(log.lines_with("cockpit/object_state: refused a non-finite pose of cup at 0.001 s"), 1);
}

}  // namespace
}  // namespace vcockpit::test
