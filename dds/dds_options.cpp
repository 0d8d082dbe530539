#include "dds/dds_options.hpp"

#include <CLI/CLI.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#ifndef VCOCKPIT_DEFAULT_QOS_FILE
#error "VCOCKPIT_DEFAULT_QOS_FILE must be defined by the build"
#endif

namespace vcockpit {
namespace {

// RTPS port arithmetic (7400 + 250 * domain + offsets) stays below 65535 up to domain 232.
constexpr int kMaxDomainId = 232;

int parse_domain(const std::string& text, const std::string& origin) {
  std::size_t used = 0;
  int value = -1;
  try {
    value = std::stoi(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || value < 0 || value > kMaxDomainId) {
    throw std::invalid_argument(origin + ": domain id must be an integer in 0.." +
                                std::to_string(kMaxDomainId) + ", got '" + text + "'");
  }
  return value;
}

}  // namespace

std::string default_qos_file() { return VCOCKPIT_DEFAULT_QOS_FILE; }

void add_dds_flags(CLI::App& app, DdsFlags& flags) {
  app.add_option("--domain", flags.domain_id,
                 "DDS domain id 0..232 (default: $VCOCKPIT_DOMAIN, else 0)")
      ->check(CLI::Range(0, kMaxDomainId));
  app.add_option("--qos", flags.qos_file,
                 "Fast DDS QoS profiles XML (default: $VCOCKPIT_QOS_FILE, else config/qos.xml)");
  app.add_option("--participant", flags.participant_profile,
                 "participant profile in the QoS file: loopback (this machine only) or lan "
                 "(default: $VCOCKPIT_PARTICIPANT, else loopback)")
      ->capture_default_str()
      ->each([&flags](const std::string&) { flags.participant_explicit = true; });
  app.add_option("--pki", flags.pki_dir,
                 "DDS Security files (scripts/make-pki DIR) for a secured participant profile "
                 "(default: $VCOCKPIT_PKI_DIR)");
  app.add_option("--identity", flags.identity,
                 "whose certificate and permissions in the --pki directory (default: "
                 "$VCOCKPIT_IDENTITY, else this program's own)");
}

DdsOptions resolve_dds_options(const DdsFlags& flags, const std::string& default_identity) {
  DdsOptions out;
  if (flags.domain_id) {
    out.domain_id = parse_domain(std::to_string(*flags.domain_id), "--domain");
  } else if (const char* env = std::getenv("VCOCKPIT_DOMAIN"); env && *env) {
    out.domain_id = parse_domain(env, "VCOCKPIT_DOMAIN");
  }
  std::string origin = "--qos";
  if (flags.qos_file) {
    out.qos_file = *flags.qos_file;
  } else if (const char* env = std::getenv("VCOCKPIT_QOS_FILE"); env && *env) {
    out.qos_file = env;
    origin = "VCOCKPIT_QOS_FILE";
  } else {
    out.qos_file = default_qos_file();
    origin = "default QoS file";
  }
  if (!std::ifstream(out.qos_file)) {
    throw std::invalid_argument(origin + ": cannot read '" + out.qos_file + "'");
  }
  out.participant_profile = flags.participant_profile;
  if (!flags.participant_explicit) {
    if (const char* env = std::getenv("VCOCKPIT_PARTICIPANT"); env && *env) out.participant_profile = env;
  }
  if (flags.pki_dir) {
    out.pki_dir = *flags.pki_dir;
    origin = "--pki";
  } else if (const char* env = std::getenv("VCOCKPIT_PKI_DIR"); env && *env) {
    out.pki_dir = env;
    origin = "VCOCKPIT_PKI_DIR";
  }
  if (!out.pki_dir.empty() && !std::filesystem::is_directory(out.pki_dir)) {
    throw std::invalid_argument(origin + ": not a directory: '" + out.pki_dir + "'");
  }
  if (!out.pki_dir.empty()) out.pki_dir = std::filesystem::absolute(out.pki_dir).string();
  out.identity = default_identity;
  if (flags.identity) {
    out.identity = *flags.identity;
  } else if (const char* env = std::getenv("VCOCKPIT_IDENTITY"); env && *env) {
    out.identity = env;
  }
  return out;
}

}  // namespace vcockpit
