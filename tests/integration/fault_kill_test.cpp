// kill -9 of every node of a running rig, in turn, at seeded random moments, twice each: the rig
// launcher restarts it, and
//   - the physics node resumes from its newest checkpoint: its first state after the kill is of
//     a simulated time at most two checkpoint intervals before the kill's (not back at 0), and
//     the cup is where the killed node had it at that time;
//   - the image generator renders again (it waits for a restarted physics node's scene);
//   - the glove driver joins the timeline where it stands (its samples go on from where the
//     killed one's were, as far on as the time it was away, not from the log's start) and the
//     hand tracks again;
// and the other nodes carry on. At the end Ctrl-C stops everything cleanly (exit 0, every node's
// restarts counted) and nothing is left in /dev/shm. How long each restart took is printed (a
// figure; the bound, 10 s, is slack for a loaded machine).
// The seed is printed; VCOCKPIT_KILL_SEED replays a run's moments.

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <signal.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <thread>

#include "common/clock.hpp"
#include "hand/glove_log.hpp"
#include "physics_node/config/scene_config.hpp"
#include "physics_node/io/world_checkpoint.hpp"
#include "tests/support/monitor_log.hpp"
#include "tests/support/process.hpp"
#include "tests/support/process_test.hpp"
#include "tests/support/test_env.hpp"

namespace vcockpit::test {
namespace {

using Json = nlohmann::json;

constexpr double kCheckpointEveryS = 0.5;

std::string config(const std::string& name) { return config_path(name); }

double glove_rate() { return sanitized() ? 0.25 : 1.0; }

// The default rig's restart policy on one hand, the bundled grasp looping in lockstep. Under the
// sanitizers the physics steps the 1 kHz log slower than real time: the glove plays at a quarter
// of its speed there, which a sanitized world on a busy machine still does not always keep up
// with (a ThreadSanitizer one stepped 110-150 steps a second): then the glove driver is held back
// (the node takes at most 256 samples a hand ahead of the world, the DDS reader 256 more), and a
// restarted driver's samples come after at most those of the killed one's.
std::string rig_yaml(const std::string& domain) {
  std::string text = "domain: " + domain + "\nqos: " + config("qos.xml") +
                     "\nparticipant: loopback\nlog: " +
                     config("glove_logs/reach_grasp_lift_release.csv") + "\nnodes:\n";
  text += "  - {name: physics_node, command: [physics_node, --lockstep, --lockstep-hands, right, "
          "--publish-hz, '250', --scene, " + config("cockpit.yaml") +
          ", --checkpoint, '{out}/state/physics.ckpt', --checkpoint-every, '" +
          std::to_string(kCheckpointEveryS) +
          "'], required: true, restart_delay_s: 0.2, restart_args: [--resume], "
          "start_delay_s: 0.3}\n";
  text += "  - {name: image_generator, command: [image_generator, --hmd, " + config("hmd.yaml") +
          ", --fps, '30'], required: false, restart_delay_s: 0.2, start_delay_s: 0.3}\n";
  text += "  - {name: glove_driver, command: [glove_driver, --source, replay, --log, '{log}', "
          "--lockstep, --rate, '" + std::to_string(glove_rate()) +
          "', --loop, --wait-readers, '1', --start-at-ns, '{start_at_ns}'], "
          "required: true, restart_delay_s: 0.2, restart_args: [--join-timeline]}\n";
  return text;
}

// The pid of the node's newest start, from the launcher's log ("started|restarted NAME (pid N)").
pid_t newest_pid(const std::string& rig_log, const std::string& node) {
  const std::string text = read_text(rig_log);
  pid_t pid = -1;
  for (const std::string verb : {"started ", "restarted "}) {
    const std::string tag = verb + node + " (pid ";
    std::size_t best = std::string::npos;
    for (auto at = text.find(tag); at != std::string::npos; at = text.find(tag, at + 1)) best = at;
    if (best == std::string::npos) continue;
    if (verb == std::string("restarted ") || pid < 0)
      pid = static_cast<pid_t>(std::stoi(text.substr(best + tag.size())));
  }
  return pid;
}

int count_of(const std::string& text, const std::string& needle) {
  int n = 0;
  for (auto at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1)) ++n;
  return n;
}

class FaultKillTest : public ProcessTest {
 protected:
  std::string domain_ = std::getenv("VCOCKPIT_DOMAIN");
  std::string monitor_path() const { return dir_ + "/monitor.txt"; }
  std::string launcher_log() const { return read_text(dir_ + "/launcher.log"); }

  // Polls the monitor's file until `found` says yes or 10 s pass (30 s under a sanitizer: the
  // lockstep world there may step slower than its glove plays, and the glove driver is held as
  // much as 768 samples ahead of it, seconds of stepping).
  template <class Found>
  bool wait_until(Found found) {
    // (a restarted image generator loads the cockpit's models again: under a sanitizer, with the
    // other core busy, its first frame took over 30 s)
    const int64_t deadline = monotonic_now_ns() + (sanitized() ? 90 : 10) * kSecond;
    while (monotonic_now_ns() < deadline) {
      if (found(MonitorLog::read(monitor_path()))) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    return false;
  }

  // The checkpoint the killed node left (read just after the kill, before the restarted node
  // could write another): the world the restarted node must resume.
  physics_io::Checkpoint saved_checkpoint(const physics::World& fresh_world) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));  // the killed node is gone
    const std::optional<physics_io::Checkpoint> saved =
        physics_io::read_checkpoint_file(dir_ + "/out/state/physics.ckpt", fresh_world);
    EXPECT_TRUE(saved.has_value()) << "no checkpoint left by the killed node";
    return saved.value_or(physics_io::Checkpoint{});
  }

  // The restarted node's first object_state the monitor sees (reliable, transient local: the
  // newest when the monitor matches the new writer) is of the checkpoint's time or a little
  // after, at or before the newest the killed node published. The killed node's states rise in
  // simulated time, so the restarted node's first is the first after the kill that does not:
  // found that way, the check does not depend on how far the monitor had written when the kill
  // came (a sanitized monitor once lagged 0.1 s behind).
  //
  // A monitor slower than a lockstep world (a sanitized one, with the glove driver's samples
  // queued) keeps only the newest state of the cup: it may never see the restarted node's states
  // at or before the killed node's newest. So a state received after this test has seen the
  // restarted node's "resumed from" (its `resumes`-th) is the restarted node's too.
  void check_physics_resumes(int64_t killed_ns, int cup_id, int resumes,
                             const physics_io::Checkpoint& saved, double gravity_mps2) {
    ASSERT_FALSE(MonitorLog::read(monitor_path()).watched.empty())
        << "object " << cup_id << " never seen before the kill";
    std::size_t resumed_at = 0;
    int64_t resume_logged_ns = -1;
    ASSERT_TRUE(wait_until([&](const MonitorLog& seen) {
      if (resume_logged_ns < 0 &&
          count_of(read_text(dir_ + "/out/logs/physics_node.log"), "resumed from ") >= resumes)
        resume_logged_ns = monotonic_now_ns();
      for (std::size_t i = 1; i < seen.watched.size(); ++i) {
        const SeenObject& w = seen.watched[i];
        if (w.received_ns > killed_ns && (w.sim_time_ns <= seen.watched[i - 1].sim_time_ns ||
                                          (resume_logged_ns > 0 && w.received_ns > resume_logged_ns))) {
          resumed_at = i;
          return true;
        }
      }
      return false;
    })) << "no object state from a restarted physics node\n" << launcher_log();
    const MonitorLog seen = MonitorLog::read(monitor_path());
    const SeenObject new_cup = seen.watched[resumed_at];
    const int64_t sim_before_ns = seen.watched[resumed_at - 1].sim_time_ns;
    const double resume_s = ns_to_seconds(new_cup.received_ns - killed_ns);
    // the checkpoint's time, from the restarted node's "resumed from PATH: T s simulated"
    const std::string physics_log = read_text(dir_ + "/out/logs/physics_node.log");
    std::size_t line_at = std::string::npos;
    for (int r = 0; r < resumes; ++r) {
      line_at = physics_log.find("resumed from ", line_at == std::string::npos ? 0 : line_at + 1);
      ASSERT_NE(line_at, std::string::npos) << physics_log;
    }
    const std::size_t time_at = physics_log.find(": ", line_at);
    ASSERT_NE(time_at, std::string::npos) << physics_log;
    const double resumed_s = std::stod(physics_log.substr(time_at + 2));
    const int64_t checkpoint_ns = saved.world.time_ns;
    std::printf("physics node killed at %.3f s simulated: resumed from %.3f s, first seen at "
                "%.3f s, publishing %.2f s after kill -9\n",
                ns_to_seconds(sim_before_ns), resumed_s, ns_to_seconds(new_cup.sim_time_ns),
                resume_s);
    // the requirement is 2 s (measured here: 0.5-0.8 s); a loaded machine gets 5x the slack
    if (!sanitized()) {
      EXPECT_LT(resume_s, 10.0);
    }
    // from the newest checkpoint the killed node completed (the one on disk when it died), not
    // from the scene's start. How far back that is depends on how far the checkpoint writer had
    // got (fsync on a busy disk): printed, not asserted
    EXPECT_NEAR(resumed_s, ns_to_seconds(checkpoint_ns), 0.0006) << "the log's time, to 1 ms";
    EXPECT_GT(checkpoint_ns, 0);
    EXPECT_GE(new_cup.sim_time_ns, checkpoint_ns);
    // The checkpoint holds the cup where the killed node had it at that time (it published every
    // 4 ms of simulated time: the nearest state before, within what the cup moves in 4 ms).
    const Eigen::Vector3d saved_cup =
        saved.world.bodies.at(static_cast<std::size_t>(cup_id)).X_GO.translation();
    const SeenObject* old_cup = nullptr;
    for (std::size_t i = 0; i < resumed_at; ++i)
      if (seen.watched[i].sim_time_ns <= checkpoint_ns) old_cup = &seen.watched[i];
    ASSERT_NE(old_cup, nullptr);
    EXPECT_LT((saved_cup - old_cup->position).norm(), 0.01)
        << "checkpoint's cup at " << saved_cup.transpose() << ", the killed node had it at "
        << old_cup->position.transpose() << " at " << ns_to_seconds(old_cup->sim_time_ns) << " s";
    // The restarted node's cup, as first seen, is that one moved by at most what the hand moved.
    // It takes up its glove from its first step, and the glove played on while it was away; the
    // monitor (a late joiner: it gets the newest state when it matches the new writer) may first
    // see it tens of steps on, a sanitized one a hundred (CI: from 3.000 s, first seen at
    // 3.096 s, the cup 24 mm higher as the wrist caught up with the lifting glove). So the 1 cm
    // bound grows by as far as the right hand moved from the checkpoint to the restarted node's
    // first hand state after that cup (a cup in the hand moves with it; one that is not, not at
    // all).
    double hand_moved_m = 0.0;
    if (new_cup.sim_time_ns > checkpoint_ns) {
      // (the monitor may not have written it yet when the cup was found: waited for)
      SeenHand hand_after;
      ASSERT_TRUE(wait_until([&](const MonitorLog& log) {
        for (const SeenHand& h : log.hands)
          if (h.id == 0 && h.received_ns >= new_cup.received_ns) {
            hand_after = h;
            return true;
          }
        return false;
      })) << "no right hand from the restarted node";
      const Eigen::Vector3d saved_wrist = saved.world.hands.at(0).X_GH.translation();
      hand_moved_m = (hand_after.position - saved_wrist).norm();
      std::printf("  the right hand moved %.1f mm from the checkpoint to %.3f s (its glove "
                  "sample of %.3f s)\n",
                  hand_moved_m * 1e3, ns_to_seconds(hand_after.sim_time_ns),
                  ns_to_seconds(hand_after.sample_time_ns));
    }
    // A cup held at the checkpoint may have been let go before it was first seen: the glove
    // played on while the node was away, and the restarted hand takes it up where it is (CI,
    // ThreadSanitizer: resumed from 10.500 s with the cup held 10 cm up, first seen at 10.692 s
    // on the console, let go as the glove set it down and opened). From there it falls at most
    // g dt^2 / 2 in the time it was not seen.
    double fall_m = 0.0;
    if (saved.world.bodies.at(static_cast<std::size_t>(cup_id)).held() && new_cup.held < 0) {
      const double unseen_s = ns_to_seconds(new_cup.sim_time_ns - checkpoint_ns);
      fall_m = 0.5 * gravity_mps2 * unseen_s * unseen_s;
      std::printf("  the cup, held at the checkpoint, was let go before %.3f s: it may have "
                  "fallen %.1f mm\n",
                  ns_to_seconds(new_cup.sim_time_ns), fall_m * 1e3);
      for (const SeenEvent& e : MonitorLog::read(monitor_path()).events)
        if (e.kind == "release" && e.t_ns > checkpoint_ns && e.t_ns <= new_cup.sim_time_ns)
          std::printf("  released at %.3f s: %s\n", ns_to_seconds(e.t_ns), e.reason.c_str());
    }
    EXPECT_LT((new_cup.position - saved_cup).norm(), 0.01 + hand_moved_m + fall_m)
        << "cup at " << new_cup.position.transpose() << " at "
        << ns_to_seconds(new_cup.sim_time_ns) << " s, the checkpoint had it at "
        << saved_cup.transpose();
  }

  void check_image_generator_renders(int64_t killed_ns) {
    int64_t first_new_end_ns = -1;
    ASSERT_TRUE(wait_until([&](const MonitorLog& seen) {
      for (std::size_t i = 1; i < seen.frames.size(); ++i) {
        if (seen.frames[i].end_ns > killed_ns && seen.frames[i].seq < seen.frames[i - 1].seq) {
          first_new_end_ns = seen.frames[i].end_ns;
          return true;
        }
      }
      return false;
    })) << "no frame from a restarted image generator\n" << launcher_log();
    const double restart_s = ns_to_seconds(first_new_end_ns - killed_ns);
    std::printf("image generator rendering again %.2f s after kill -9\n", restart_s);
    // here it dies right after the physics node's own restart (the seeded order), and the new
    // one waits for the restarted node's scene (measured here: 0.6-1.2 s, once 2.27 s); the
    // bound is generous slack for a loaded machine, not the figure
    if (!sanitized()) {
      EXPECT_LT(restart_s, 10.0);
    }
  }

  // The restarted driver's samples are stamped (source_stamp_ns, the driver's clock) after the
  // kill. The rig's timeline puts the log's first sample at the launcher's start_at_ns, and
  // a sample's log time advances with its stamp at the replay's rate from there: the first
  // tracked hand made of the restarted driver's samples must be on that line (a driver that
  // started its log over, or sent what was due while it was away in a burst, would not).
  void check_glove_joins(int64_t killed_ns, int64_t log_start_ns) {
    const std::string launcher = read_text(dir_ + "/launcher.log");
    const std::string tag = "start_at_ns=";
    const auto at = launcher.find(tag);
    ASSERT_NE(at, std::string::npos) << "the launcher names the rig's start\n" << launcher;
    const int64_t start_at_ns = std::stoll(launcher.substr(at + tag.size()));
    auto off_timeline_s = [&](const SeenHand& h) {
      return ns_to_seconds(h.sample_time_ns - log_start_ns) -
             glove_rate() * ns_to_seconds(h.source_stamp_ns - start_at_ns);
    };
    const MonitorLog before = MonitorLog::read(monitor_path());
    const SeenHand* first = nullptr;
    for (const SeenHand& h : before.hands)
      if (h.tracking && !first) first = &h;
    ASSERT_NE(first, nullptr) << "no tracked hand before the kill";
    // the first start is on the line too, unless its reader matched after the rig's start
    // (the driver warns; a sanitized physics node loads the cockpit for over 3 s)
    std::printf("the glove driver's first start: %.1f ms off the rig's timeline\n",
                off_timeline_s(*first) * 1e3);
    if (!sanitized()) {
      EXPECT_NEAR(off_timeline_s(*first), 0.0, 0.05) << "first start late";
    }
    SeenHand joined;
    ASSERT_TRUE(wait_until([&](const MonitorLog& seen) {
      for (const SeenHand& h : seen.hands) {
        if (h.tracking && h.source_stamp_ns > killed_ns) {
          joined = h;
          return true;
        }
      }
      return false;
    })) << "the hand did not track a restarted glove driver's samples\n" << launcher_log();
    std::printf("glove driver killed: the hand tracks its restart %.2f s after kill -9, at %.3f s "
                "of the log, %.1f ms off the rig's timeline\n",
                ns_to_seconds(joined.received_ns - killed_ns), ns_to_seconds(joined.sample_time_ns),
                off_timeline_s(joined) * 1e3);
    // on 2 cores beside a rendering image generator the restart is 0.2 s of restart delay,
    // 0.1-0.5 s to start, up to 0.65 s to match the physics node's reader and 0.25 s to the
    // first delivered sample (measured here: 1.3-2.15 s, 3.74 s with the machine busy); the
    // bound is generous slack, not the figure
    if (!sanitized()) {
      EXPECT_LT(ns_to_seconds(joined.received_ns - killed_ns), 10.0);
    }
    EXPECT_NEAR(off_timeline_s(joined), 0.0, 0.05) << "not joined where the timeline stands";
  }
};

TEST_F(FaultKillTest, EachNodeKilledTwiceAtSeededMomentsIsRestartedAndTheRigCarriesOn) {
  const char* seed_text = std::getenv("VCOCKPIT_KILL_SEED");
  const unsigned seed = seed_text ? static_cast<unsigned>(std::strtoul(seed_text, nullptr, 10)) : 20261127u;
  std::printf("kill moments seeded with %u (VCOCKPIT_KILL_SEED)\n", seed);
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> pause_s(2.0, 4.0);

  const physics::World fresh_world(load_scene(config("cockpit.yaml")));  // reads checkpoints
  const int cup_id = fresh_world.scene().find_object("cup");
  ASSERT_GE(cup_id, 0);
  const int64_t log_start_ns =
      hand::read_glove_log(config("glove_logs/reach_grasp_lift_release.csv"),
                           fresh_world.scene().hands[0])
          .samples.front()
          .t_ns;
  ChildProcess monitor({bin_dir() + "/test_cockpit_monitor", "--out", monitor_path(),
                        "--watch-object", std::to_string(cup_id)},
                       dds_test_env(), dir_ + "/monitor.log");
  std::ofstream(dir_ + "/rig.yaml") << rig_yaml(domain_);
  ChildProcess rig({bin_dir() + "/rig_launcher", dir_ + "/rig.yaml", "--out", dir_ + "/out", "--quiet"},
                   {}, dir_ + "/launcher.log");
  const std::string rig_log = dir_ + "/launcher.log";
  ASSERT_TRUE(wait_for_line(monitor_path(), "frame seq=30 ", 30 * kSecond)) << launcher_log();
  ASSERT_TRUE(wait_for_line(monitor_path(), "hand id=0", 30 * kSecond)) << launcher_log();

  const std::string order[] = {"physics_node", "image_generator", "glove_driver"};
  for (int kill = 0; kill < 6; ++kill) {
    const std::string& node = order[kill % 3];
    std::this_thread::sleep_for(std::chrono::duration<double>(pause_s(random)));
    const pid_t pid = newest_pid(rig_log, node);
    ASSERT_GT(pid, 0) << launcher_log();
    ASSERT_EQ(::kill(pid, 0), 0) << node << " (pid " << pid << ") is not running\n" << launcher_log();
    const int64_t killed_ns = monotonic_now_ns();
    ::kill(pid, SIGKILL);
    SCOPED_TRACE("kill " + std::to_string(kill + 1) + ": " + node);
    if (node == "physics_node") {
      const physics_io::Checkpoint saved = saved_checkpoint(fresh_world);
      check_physics_resumes(killed_ns, cup_id, kill / 3 + 1, saved,
                            fresh_world.scene().gravity_mps2.norm());
    } else if (node == "image_generator") {
      check_image_generator_renders(killed_ns);
    } else {
      check_glove_joins(killed_ns, log_start_ns);
    }
    if (HasFatalFailure()) break;
  }

  std::this_thread::sleep_for(std::chrono::seconds(1));
  rig.signal(SIGINT);
  ASSERT_EQ(rig.wait(20 * kSecond), 0) << launcher_log();
  EXPECT_EQ(monitor.stop(), 0);
  const Json summary = Json::parse(read_text(dir_ + "/out/summary.json"));
  for (const std::string& node : order) {
    EXPECT_EQ(summary["nodes"][node], Json({{"exit_status", 0}, {"restarts", 2}})) << node;
  }
  const std::string physics_log = read_text(dir_ + "/out/logs/physics_node.log");
  EXPECT_EQ(count_of(physics_log, "resumed from "), 2) << physics_log;
  EXPECT_EQ(count_of(physics_log, "not resumed"), 0) << physics_log;
  EXPECT_EQ(count_of(read_text(dir_ + "/out/logs/glove_driver.log"), "joined the timeline"), 2);
}

// Real time: a node stopped after 1.5 s left its world in the checkpoint, and one started with
// --resume goes on from there; a damaged checkpoint is refused with why, kept aside as .bad, and
// the node starts from the scene; flags that cannot work are refused at start.
TEST_F(FaultKillTest, ARealTimeNodeResumesFromItsCheckpointAndRefusesADamagedOne) {
  const std::string checkpoint = dir_ + "/state/physics.ckpt";
  // "stopped after N steps" (this run's own) and "resumed from PATH: T s simulated, M steps"
  auto stopped_steps = [&](const std::string& log) -> uint64_t {
    const auto at = log.find("stopped after ");
    return at == std::string::npos ? 0 : std::stoull(log.substr(at + 14));
  };
  auto resumed = [&](const std::string& log, double& simulated_s, uint64_t& steps) {
    const auto at = log.find("resumed from " + checkpoint + ": ");
    if (at == std::string::npos) return false;
    std::size_t used = 0;
    const std::string rest = log.substr(at + checkpoint.size() + 15);
    simulated_s = std::stod(rest, &used);
    steps = std::stoull(rest.substr(rest.find(", ", used) + 2));
    return true;
  };

  ChildProcess first = start("physics_node", {"--checkpoint", checkpoint, "--duration", "1.5"},
                             "first.log");
  ASSERT_EQ(first.wait(30 * kSecond), 0) << text("first.log");
  EXPECT_NE(text("first.log").find("checkpoints: "), std::string::npos) << text("first.log");
  const uint64_t first_steps = stopped_steps(text("first.log"));
  ASSERT_GT(first_steps, 0u) << text("first.log");
  // the world at the first run's stop, however many steps a loaded machine let it take: its
  // step count and its time (1 ms steps), not 0
  ChildProcess second = start("physics_node", {"--checkpoint", checkpoint, "--resume", "--duration",
                                               "0.5"},
                              "second.log");
  ASSERT_EQ(second.wait(30 * kSecond), 0) << text("second.log");
  double resumed_s = 0;
  uint64_t resumed_steps = 0;
  ASSERT_TRUE(resumed(text("second.log"), resumed_s, resumed_steps)) << text("second.log");
  EXPECT_EQ(resumed_steps, first_steps) << text("second.log");
  EXPECT_NEAR(resumed_s, 1e-3 * static_cast<double>(first_steps), 1e-3) << text("second.log");
  // the second run counts its own steps, not the resumed world's: a third run resumes the sum
  const uint64_t second_steps = stopped_steps(text("second.log"));
  ASSERT_GT(second_steps, 0u) << text("second.log");
  ChildProcess third = start("physics_node", {"--checkpoint", checkpoint, "--resume", "--duration",
                                              "0.2"},
                             "third.log");
  ASSERT_EQ(third.wait(30 * kSecond), 0) << text("third.log");
  ASSERT_TRUE(resumed(text("third.log"), resumed_s, resumed_steps)) << text("third.log");
  EXPECT_EQ(resumed_steps, first_steps + second_steps) << text("third.log");

  // one byte changed in the middle: the checksum catches it
  std::string bytes = read_text(checkpoint);
  bytes[bytes.size() / 2] ^= 0x01;
  std::ofstream(checkpoint, std::ios::binary | std::ios::trunc) << bytes;
  ChildProcess damaged = start("physics_node", {"--checkpoint", checkpoint, "--resume",
                                                "--duration", "0.3"},
                               "damaged.log");
  ASSERT_EQ(damaged.wait(30 * kSecond), 0) << text("damaged.log");
  EXPECT_NE(text("damaged.log").find("not resumed: " + checkpoint + ": its checksum does not match"),
            std::string::npos)
      << text("damaged.log");
  EXPECT_TRUE(std::filesystem::exists(checkpoint + ".bad"));
  EXPECT_TRUE(std::filesystem::exists(checkpoint)) << "the new run saves its own";

  expect_each_refused("physics_node", {
      {{"--resume"}, "--resume needs --checkpoint"},
      {{"--offline", "--checkpoint", checkpoint}, "belong to the DDS modes"},
      {{"--checkpoint", checkpoint, "--checkpoint-every", "0"}, "--checkpoint-every"},
      {{"--checkpoint", "/proc/no/such/dir/p.ckpt"}, "--checkpoint: cannot create"},
  });
}

}  // namespace
}  // namespace vcockpit::test
