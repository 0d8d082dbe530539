// The rig launcher's monitor names the controls it reports from cockpit/control_info, whenever
// that arrives: a control's state and events taken before its info (the topics are independent,
// and under load the info came second) are named once it comes, not left as "control 3" beside
// the named ones (the full rig's summary once listed 22 controls of 11).

#include <gtest/gtest.h>

#include <chrono>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include "dds/dds_options.hpp"
#include "dds/dds_participant.hpp"
#include "launcher/rig_monitor.hpp"

namespace vcockpit::test {
namespace {

constexpr int64_t kWait_ns = 10'000'000'000;

// Polls until `done` or about 10 s.
template <class Done>
bool poll_until(rig::RigMonitor& monitor, Done done) {
  for (int tries = 0; tries < 1000; ++tries) {
    monitor.poll();
    if (done()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return false;
}

TEST(RigMonitor, NamesAControlWhoseStateCameBeforeItsInfo) {
  DdsParticipant publisher(resolve_dds_options(DdsFlags{}), "rig_monitor_test_pub");
  DdsParticipant listener(resolve_dds_options(DdsFlags{}), "rig_monitor_test");
  auto infos = publisher.make_writer<cockpit::ControlInfo>("state");
  auto states = publisher.make_writer<cockpit::ControlState>("state");
  auto events = publisher.make_writer<cockpit::ControlEvent>("event");
  rig::RigMonitor monitor(listener);
  ASSERT_TRUE(states.wait_for_matched(1, kWait_ns));
  ASSERT_TRUE(events.wait_for_matched(1, kWait_ns));
  ASSERT_TRUE(infos.wait_for_matched(1, kWait_ns));

  cockpit::ControlState state;
  state.control_id(3);
  state.position(1);
  states.write(state);
  cockpit::ControlEvent event;
  event.control_id(3);
  event.sim_time_ns(2'000'000'000);
  event.from_position(0);
  event.to_position(1);
  event.cause(cockpit::GRASPED);
  event.link(-1);
  events.write(event);
  // taken before any info: numbered
  ASSERT_TRUE(poll_until(monitor, [&] {
    return monitor.control_positions().count("control 3") == 1 && monitor.control_events().size() == 1;
  }));
  EXPECT_EQ(monitor.control_positions().at("control 3"), "1");

  cockpit::ControlInfo info;
  info.control_id(3);
  info.name("flaps");
  info.position_count(3);
  info.position_names("up|approach|landing|");
  infos.write(info);
  ASSERT_TRUE(poll_until(monitor, [&] { return monitor.control_positions().count("flaps") == 1; }));
  const std::map<std::string, std::string> positions = monitor.control_positions();
  EXPECT_EQ(positions.size(), 1u) << "the numbered entry is gone";
  EXPECT_EQ(positions.at("flaps"), "approach");
  const std::vector<rig::SeenControlEvent> seen = monitor.control_events();
  ASSERT_EQ(seen.size(), 1u);
  EXPECT_EQ(seen[0].control, "flaps");
  EXPECT_EQ(seen[0].from, "up");
  EXPECT_EQ(seen[0].to, "approach");
  EXPECT_EQ(seen[0].cause, "grasped");
  EXPECT_EQ(seen[0].t_s, 2.0);
}

}  // namespace
}  // namespace vcockpit::test
