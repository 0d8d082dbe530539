#pragma once
// Base fixture of the integration tests: a temp directory of the test's own, the test's DDS
// domain in the environment of the processes it starts, and a /dev/shm check at the end (what a
// test left there is removed, and counted as a failure unless the test killed a process on
// purpose).

#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "tests/support/monitor_log.hpp"
#include "tests/support/process.hpp"
#include "tests/support/test_env.hpp"

namespace vcockpit::test {

constexpr int64_t kSecond = 1'000'000'000;

inline std::string config_path(const std::string& name) { return source_dir() + "/config/" + name; }

// True in the sanitizer build, where wall-clock limits (rates, restart times) are not asserted.
inline bool sanitized() {
  const char* value = std::getenv("VCOCKPIT_SANITIZED");
  return value && std::string(value) == "1";
}

class ProcessTest : public ::testing::Test {
 protected:
  void SetUp() override { shm_before_ = list_dds_shm(); }
  void TearDown() override {
    const auto leftovers = new_entries(shm_before_, list_dds_shm());
    remove_dds_shm(leftovers);
    if (expect_clean_shm_) {
      EXPECT_TRUE(leftovers.empty()) << leftovers.size() << " files left in /dev/shm, e.g. "
                                     << (leftovers.empty() ? "" : leftovers.front());
    }
  }

  // Starts build/bin/<exe> with the test's environment; its output goes to <dir>/<log>.
  ChildProcess start(const std::string& exe, std::vector<std::string> args, const std::string& log) {
    args.insert(args.begin(), bin_dir() + "/" + exe);
    return ChildProcess(args, env_, dir_ + "/" + log);
  }
  std::string text(const std::string& name) const { return read_text(dir_ + "/" + name); }

  // A command line that must be refused: a non-zero exit (not a hang) whose output says `message`.
  struct BadRun {
    std::vector<std::string> args;
    std::string message;
  };
  void expect_each_refused(const std::string& exe, const std::vector<BadRun>& runs) {
    for (std::size_t i = 0; i < runs.size(); ++i) {
      const std::string log = "bad" + std::to_string(i) + ".log";
      ChildProcess child = start(exe, runs[i].args, log);
      const int code = child.wait(20 * kSecond);
      EXPECT_NE(code, 0) << "case " << i;
      EXPECT_NE(code, -1) << "case " << i << " still running";
      EXPECT_NE(text(log).find(runs[i].message), std::string::npos)
          << "case " << i << ": " << text(log);
    }
  }

  std::string dir_ = make_temp_dir("it");
  std::map<std::string, std::string> env_ = dds_test_env();
  std::vector<std::string> shm_before_;
  bool expect_clean_shm_ = true;
};

// Length-prefixed records as tests/integration/hand_sample_sub writes them.
inline std::vector<std::vector<uint8_t>> read_records(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::vector<std::vector<uint8_t>> records;
  uint32_t size = 0;
  while (in.read(reinterpret_cast<char*>(&size), sizeof size)) {
    std::vector<uint8_t> record(size);
    if (!in.read(reinterpret_cast<char*>(record.data()), size)) break;
    records.push_back(std::move(record));
  }
  return records;
}

}  // namespace vcockpit::test
