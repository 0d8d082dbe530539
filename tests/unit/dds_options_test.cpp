#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <iterator>

#include "dds/dds_options.hpp"

namespace vcockpit {
namespace {

class DdsOptionsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    unsetenv("VCOCKPIT_DOMAIN");
    unsetenv("VCOCKPIT_QOS_FILE");
    unsetenv("VCOCKPIT_PKI_DIR");
    unsetenv("VCOCKPIT_IDENTITY");
  }
};

TEST_F(DdsOptionsTest, DefaultsToDomainZeroAndTheProjectQosFile) {
  const auto options = resolve_dds_options({});
  EXPECT_EQ(options.domain_id, 0);
  EXPECT_EQ(options.qos_file, default_qos_file());
  EXPECT_EQ(options.participant_profile, "loopback");
}

TEST_F(DdsOptionsTest, FlagBeatsEnvironment) {
  setenv("VCOCKPIT_DOMAIN", "17", 1);
  EXPECT_EQ(resolve_dds_options({}).domain_id, 17);
  DdsFlags flags;
  flags.domain_id = 5;
  EXPECT_EQ(resolve_dds_options(flags).domain_id, 5);
}

TEST_F(DdsOptionsTest, BadEnvironmentDomainNamesTheVariable) {
  setenv("VCOCKPIT_DOMAIN", "300", 1);
  try {
    resolve_dds_options({});
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("VCOCKPIT_DOMAIN"), std::string::npos) << e.what();
  }
  setenv("VCOCKPIT_DOMAIN", "7x", 1);
  EXPECT_THROW(resolve_dds_options({}), std::invalid_argument);
}

TEST_F(DdsOptionsTest, UnreadableQosFileIsAnError) {
  DdsFlags flags;
  flags.qos_file = "/nonexistent/qos.xml";
  EXPECT_THROW(resolve_dds_options(flags), std::invalid_argument);
}

TEST_F(DdsOptionsTest, DefaultQosProfileKeepsTrafficOnLoopback) {
  // The network rule: the default participant profile whitelists 127.0.0.1 and turns off the
  // builtin (all-interface) transports.
  std::ifstream in(default_qos_file());
  const std::string xml((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto loopback = xml.find("profile_name=\"loopback\" is_default_profile=\"true\"");
  ASSERT_NE(loopback, std::string::npos);
  const auto end = xml.find("</participant>", loopback);
  const std::string profile = xml.substr(loopback, end - loopback);
  EXPECT_NE(profile.find("<useBuiltinTransports>false</useBuiltinTransports>"), std::string::npos);
  EXPECT_NE(profile.find("<transport_id>udp_loopback</transport_id>"), std::string::npos);
  EXPECT_NE(profile.find("127.0.0.1"), std::string::npos);
  const auto udp = xml.find("<transport_id>udp_loopback</transport_id>");
  const auto udp_end = xml.find("</transport_descriptor>", udp);
  EXPECT_NE(xml.substr(udp, udp_end - udp).find("<address>127.0.0.1</address>"),
            std::string::npos);
}

// The secured profile keeps to loopback too, and names the three security plugins (the files
// come from --pki at run time).
TEST_F(DdsOptionsTest, TheSecureProfileIsLoopbackWithTheSecurityPlugins) {
  std::ifstream in(default_qos_file());
  const std::string xml((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto secure = xml.find("profile_name=\"secure\"");
  ASSERT_NE(secure, std::string::npos);
  const std::string profile = xml.substr(secure, xml.find("</participant>", secure) - secure);
  EXPECT_NE(profile.find("<useBuiltinTransports>false</useBuiltinTransports>"), std::string::npos);
  EXPECT_NE(profile.find("<transport_id>udp_loopback</transport_id>"), std::string::npos);
  EXPECT_EQ(profile.find("<transport_id>shm</transport_id>"), std::string::npos);
  for (const char* plugin : {"builtin.PKI-DH", "builtin.Access-Permissions", "builtin.AES-GCM-GMAC"})
    EXPECT_NE(profile.find(plugin), std::string::npos) << plugin;
  EXPECT_EQ(profile.find("file://"), std::string::npos) << "no machine's files in the project's QoS";
}

TEST_F(DdsOptionsTest, PkiDirectoryAndIdentityFromFlagsEnvironmentOrTheProgram) {
  EXPECT_TRUE(resolve_dds_options({}).pki_dir.empty());
  EXPECT_EQ(resolve_dds_options({}, "physics_node").identity, "physics_node");
  setenv("VCOCKPIT_PKI_DIR", "/tmp", 1);
  setenv("VCOCKPIT_IDENTITY", "rig_monitor", 1);
  auto options = resolve_dds_options({}, "physics_node");
  EXPECT_EQ(options.pki_dir, "/tmp");
  EXPECT_EQ(options.identity, "rig_monitor");
  DdsFlags flags;
  flags.pki_dir = "/";
  flags.identity = "glove_driver";
  options = resolve_dds_options(flags, "physics_node");
  EXPECT_EQ(options.pki_dir, "/");
  EXPECT_EQ(options.identity, "glove_driver");
  flags.pki_dir = "/nonexistent/pki";
  try {
    resolve_dds_options(flags);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("--pki: not a directory: '/nonexistent/pki'"),
              std::string::npos) << e.what();
  }
  flags.pki_dir.reset();
  setenv("VCOCKPIT_PKI_DIR", "/nonexistent/pki", 1);
  try {
    resolve_dds_options(flags);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("VCOCKPIT_PKI_DIR"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace vcockpit
