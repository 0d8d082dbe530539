#pragma once
// Where a node's DDS settings come from: flags first, then environment, then defaults.
//   --domain N        or VCOCKPIT_DOMAIN     (default 0)
//   --qos FILE        or VCOCKPIT_QOS_FILE   (default: the project's config/qos.xml)
//   --participant P   or VCOCKPIT_PARTICIPANT: participant profile in the QoS file
//                     (default "loopback": 127.0.0.1 only)

#include <optional>
#include <string>

namespace CLI {
class App;
}

namespace vcockpit {

struct DdsOptions {
  int domain_id = 0;
  std::string qos_file;
  std::string participant_profile = "loopback";
};

// Flags as given on the command line, before the environment and defaults are applied.
struct DdsFlags {
  std::optional<int> domain_id;
  std::optional<std::string> qos_file;
  std::string participant_profile = "loopback";
  bool participant_explicit = false;  // given on the command line (beats the environment)
};

// Adds --domain, --qos and --participant to a CLI11 app.
void add_dds_flags(CLI::App& app, DdsFlags& flags);

// Applies environment and defaults. Throws std::invalid_argument naming the flag or variable
// (domain outside 0..232, unreadable QoS file).
DdsOptions resolve_dds_options(const DdsFlags& flags);

// The QoS file used when neither flag nor environment names one.
std::string default_qos_file();

}  // namespace vcockpit
