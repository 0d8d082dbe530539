// The physics node's publisher sends no NaN or infinity (state_publisher.hpp): a world restored
// into a state with a non-finite body publishes every other object and not that one, and a node
// status with a non-finite rate goes out with -1 in its place; each refusal is counted. Its
// keep-last-1 state topics keep every instance's sample within the history span of the newest
// however long it runs (static objects and controls at rest are written again). In one
// process, over loopback DDS on the test's own domain.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <set>

#include "dds/dds_options.hpp"
#include "physics_node/config/scene_config.hpp"
#include "physics_node/node/state_publisher.hpp"
#include "tests/support/test_env.hpp"
#include "tests/support/test_files.hpp"

namespace vcockpit::test {
namespace {

constexpr int64_t kWait_ns = 5'000'000'000;

TEST(StatePublisher, PublishesNoNonFiniteValue) {
  dds_test_env();  // this test's own domain, from VCOCKPIT_DOMAIN
  physics::World world(load_scene(source_dir() + "/config/cockpit.yaml"));
  const int ball = world.scene().find_object("ball");
  ASSERT_GE(ball, 0);
  physics::WorldState broken = world.state();
  broken.bodies[static_cast<std::size_t>(ball)].v_G.x() = std::numeric_limits<double>::quiet_NaN();
  world.restore(broken);

  DdsParticipant participant(resolve_dds_options(DdsFlags{}), "state_publisher_test");
  auto objects = participant.make_reader<cockpit::ObjectState>("state");
  auto statuses = participant.make_reader<cockpit::NodeStatus>("state");
  physics_node::StatePublisher publisher(participant, world);
  ASSERT_TRUE(objects.wait_for_matched(1, kWait_ns));
  ASSERT_TRUE(statuses.wait_for_matched(1, kWait_ns));

  publisher.publish_state(world, {{{}, true}});
  std::set<uint32_t> received;
  for (int tries = 0; tries < 50 && received.size() < 3; ++tries) {
    objects.wait_for_data(100'000'000);
    cockpit::ObjectState s;
    while (objects.take(s)) {
      received.insert(s.object_id());
      EXPECT_TRUE(std::isfinite(s.linear_velocity_mps().x())) << s.object_id();
    }
  }
  std::set<uint32_t> expected;
  for (std::size_t i = 0; i < world.scene().objects.size(); ++i)
    if (world.scene().objects[i].dynamic && static_cast<int>(i) != ball) expected.insert(static_cast<uint32_t>(i));
  EXPECT_EQ(received, expected) << "every dynamic object but the broken ball";
  EXPECT_EQ(publisher.non_finite_refused(), 1u);

  cockpit::NodeStatus status;
  status.node_name("physics_node");
  status.loop_rate_hz(std::numeric_limits<double>::infinity());
  status.input_rate_hz(250.0);
  publisher.publish_status(status);
  cockpit::NodeStatus got;
  bool have = false;
  for (int tries = 0; tries < 50 && !have; ++tries) {
    statuses.wait_for_data(100'000'000);
    have = statuses.take(got);
  }
  ASSERT_TRUE(have);
  EXPECT_EQ(got.loop_rate_hz(), -1.0) << "the documented sentinel";
  EXPECT_EQ(got.input_rate_hz(), 250.0);
  EXPECT_EQ(publisher.non_finite_refused(), 2u);
}

// An object with a look (config/cockpit.yaml's shell) is described to the renderers as its look,
// the model's part, while the physics collides with its box; one without is described as its
// shape.
TEST(StatePublisher, DescribesAnObjectWithALookAsItsLook) {
  dds_test_env();
  physics::World world(load_scene(source_dir() + "/config/cockpit.yaml"));
  const int panel = world.scene().find_object("instrument_panel");
  const int cup = world.scene().find_object("cup");
  ASSERT_GE(panel, 0);
  ASSERT_GE(cup, 0);
  DdsParticipant participant(resolve_dds_options(DdsFlags{}), "state_publisher_test");
  auto infos = participant.make_reader<cockpit::ObjectInfo>("state");
  physics_node::StatePublisher publisher(participant, world);
  ASSERT_TRUE(infos.wait_for_matched(1, kWait_ns));
  publisher.publish_object_info(world);
  std::map<uint32_t, cockpit::ObjectInfo> got;
  for (int tries = 0; tries < 50 && got.size() < world.scene().objects.size(); ++tries) {
    infos.wait_for_data(100'000'000);
    cockpit::ObjectInfo info;
    while (infos.take(info)) got[info.object_id()] = info;
  }
  ASSERT_EQ(got.count(static_cast<uint32_t>(panel)), 1u);
  const cockpit::ObjectInfo& p = got[static_cast<uint32_t>(panel)];
  EXPECT_EQ(p.shape(), cockpit::MESH);
  EXPECT_EQ(p.mesh_node().to_string(), "InstrumentPanel");
  EXPECT_EQ(p.mesh_file().to_string(),
            world.scene().objects[static_cast<std::size_t>(panel)].look->mesh_source.file);
  EXPECT_NEAR(p.dimensions_m()[1], 1.10, 0.002) << "the look's extents: the panel's span";
  ASSERT_EQ(got.count(static_cast<uint32_t>(cup)), 1u);
  EXPECT_EQ(got[static_cast<uint32_t>(cup)].shape(), cockpit::CYLINDER);
}

// Each instance's kept sample, as a late-joining (transient local) reader gets it: its writer's
// sequence number by instance.
template <class T, class Id>
std::map<uint32_t, int64_t> kept_sequence_numbers(Reader<T>& reader, std::size_t instances, Id id) {
  std::map<uint32_t, int64_t> seq;
  T sample;
  dds::SampleInfo info;
  for (int tries = 0; tries < 50 && seq.size() < instances; ++tries) {
    reader.wait_for_data(100'000'000);
    while (reader.take(sample, &info)) seq[id(sample)] = info.sample_identity.sequence_number().to64long();
  }
  return seq;
}

int64_t span(const std::map<uint32_t, int64_t>& seq) {
  const auto [oldest, newest] = std::minmax_element(
      seq.begin(), seq.end(), [](const auto& a, const auto& b) { return a.second < b.second; });
  return newest->second - oldest->second;
}

// The cause of the soak's growing reader CPU (state_publisher.hpp, "History span"): on a
// keep-last-1 topic, static objects written once and controls at rest kept their first
// sequence numbers while the moving instances went on, and Fast DDS walks the hole between them
// on every heartbeat. After many cycles with one control moving, no kept sample of object_state
// or control_state may lie history_span_samples or more behind its writer's newest.
TEST(StatePublisher, KeepsEveryInstanceWithinTheHistorySpan) {
  dds_test_env();
  physics::World world(load_scene(source_dir() + "/config/cockpit.yaml"));
  const std::size_t objects = world.scene().objects.size();
  const std::size_t controls = world.scene().controls.size();
  const int knob = world.scene().find_control("heading_bug");
  ASSERT_GE(knob, 0);
  const uint64_t object_span = physics_node::history_span_samples(objects);
  const uint64_t control_span = physics_node::history_span_samples(controls);

  DdsParticipant participant(resolve_dds_options(DdsFlags{}), "state_publisher_test");
  physics_node::StatePublisher publisher(participant, world);
  publisher.publish_object_info(world);  // the static objects' one state sample
  // the knob turns every cycle (one control_state each), the others rest; each dynamic object
  // is written every cycle
  physics::WorldState state = world.state();
  const uint64_t cycles = 4 * std::max(object_span, control_span);
  for (uint64_t c = 0; c < cycles; ++c) {
    state.controls[static_cast<std::size_t>(knob)].q = 1e-4 * static_cast<double>(c % 1000);
    world.restore(state);
    publisher.publish_state(world, {});
  }

  auto object_reader = participant.make_reader<cockpit::ObjectState>("state");
  auto control_reader = participant.make_reader<cockpit::ControlState>("state");
  const auto object_seq = kept_sequence_numbers(object_reader, objects,
                                                [](const cockpit::ObjectState& s) { return s.object_id(); });
  const auto control_seq = kept_sequence_numbers(
      control_reader, controls, [](const cockpit::ControlState& s) { return s.control_id(); });
  ASSERT_EQ(object_seq.size(), objects) << "every object's kept sample";
  ASSERT_EQ(control_seq.size(), controls) << "every control's kept sample";
  EXPECT_LT(span(object_seq), static_cast<int64_t>(object_span)) << "object_state";
  EXPECT_LT(span(control_seq), static_cast<int64_t>(control_span)) << "control_state";
}

}  // namespace
}  // namespace vcockpit::test
