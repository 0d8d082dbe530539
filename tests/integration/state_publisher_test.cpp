// The physics node's publisher sends no NaN or infinity (state_publisher.hpp): a world restored
// into a state with a non-finite body publishes every other object and not that one, and a node
// status with a non-finite rate goes out with -1 in its place; each refusal is counted. In one
// process, over loopback DDS on the test's own domain.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>

#include "common/dds_options.hpp"
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

}  // namespace
}  // namespace vcockpit::test
