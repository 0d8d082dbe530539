// The physics node's checkpoint writer thread (physics_node/node/checkpoint_writer.hpp): what is
// offered is encoded and written whole, the newest wins, a flush waits for the disk, and a file
// that cannot be written is counted and logged while the node goes on.

#include "physics_node/node/checkpoint_writer.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "physics_node/config/scene_config.hpp"
#include "physics_node/physics/world_state_hash.hpp"

namespace vcockpit::physics_node {
namespace {

std::string source_dir() {
  const char* dir = std::getenv("VCOCKPIT_SOURCE_DIR");
  return dir ? dir : ".";
}

TEST(CheckpointWriter, TheNewestOfferedStateIsOnDiskAfterAFlushAndDecodesToIt) {
  const physics::World fresh(load_scene(source_dir() + "/config/cockpit.yaml"));
  physics::World world(fresh.scene());
  const std::string dir = ::testing::TempDir() + "checkpoint_writer_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/physics.ckpt";
  CheckpointWriter writer(path, physics_io::scene_fingerprint(fresh));
  physics_io::Checkpoint checkpoint;
  for (int i = 0; i < 20; ++i) {
    world.step();
    checkpoint.world = world.state();
    checkpoint.frozen = i % 2 == 1;
    writer.offer(checkpoint);
  }
  writer.flush();
  EXPECT_EQ(writer.written() + writer.superseded(), 20u);
  EXPECT_GE(writer.written(), 1u);
  EXPECT_EQ(writer.failed(), 0u);
  const auto read = physics_io::read_checkpoint_file(path, fresh);
  ASSERT_TRUE(read.has_value());
  EXPECT_EQ(physics::hash_world_state(read->world), physics::hash_world_state(world.state()));
  EXPECT_TRUE(read->frozen);
  EXPECT_FALSE(std::filesystem::exists(path + ".partial"));
}

TEST(CheckpointWriter, AFileThatCannotBeWrittenIsCountedAndTheWriterGoesOn) {
  const physics::World fresh(load_scene(source_dir() + "/config/cockpit.yaml"));
  CheckpointWriter writer("/nonexistent-dir/for/checkpoints/physics.ckpt",
                          physics_io::scene_fingerprint(fresh));
  physics_io::Checkpoint checkpoint{fresh.state(), false};
  writer.offer(checkpoint);
  writer.flush();
  checkpoint.world = fresh.state();
  writer.offer(checkpoint);
  writer.flush();
  EXPECT_EQ(writer.failed(), 2u);
  EXPECT_EQ(writer.written(), 0u);
}

}  // namespace
}  // namespace vcockpit::physics_node
