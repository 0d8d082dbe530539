#pragma once
// Environment for the real processes a test starts: the test's own DDS domain (set per test by
// CMake as VCOCKPIT_DOMAIN) and the project's loopback-only QoS file.

#include <cstdlib>
#include <map>
#include <stdexcept>
#include <string>

namespace vcockpit::test {

inline std::map<std::string, std::string> dds_test_env() {
  const char* domain = std::getenv("VCOCKPIT_DOMAIN");
  if (!domain || std::string(domain) == "0") {
    throw std::runtime_error("integration tests need their own non-zero VCOCKPIT_DOMAIN");
  }
  return {{"VCOCKPIT_DOMAIN", domain}};
}

}  // namespace vcockpit::test
