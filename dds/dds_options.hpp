#pragma once
// Where a node's DDS settings come from: flags first, then environment, then defaults.
//   --domain N        or VCOCKPIT_DOMAIN     (default 0)
//   --qos FILE        or VCOCKPIT_QOS_FILE   (default: the project's config/qos.xml)
//   --participant P   or VCOCKPIT_PARTICIPANT: participant profile in the QoS file
//                     (default "loopback": 127.0.0.1 only; "secure": the same with DDS Security)
//   --pki DIR         or VCOCKPIT_PKI_DIR: the DDS Security files (scripts/make-pki), for a
//                     secured profile
//   --identity NAME   or VCOCKPIT_IDENTITY: whose certificate, key and permissions in DIR
//                     (default: the program's own: glove_driver, physics_node, ...)

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
  std::string pki_dir;   // empty: none
  std::string identity;  // the certificate's and permissions' name in pki_dir
};

// Flags as given on the command line, before the environment and defaults are applied.
struct DdsFlags {
  std::optional<int> domain_id;
  std::optional<std::string> qos_file;
  std::string participant_profile = "loopback";
  bool participant_explicit = false;  // given on the command line (beats the environment)
  std::optional<std::string> pki_dir;
  std::optional<std::string> identity;
};

// Adds --domain, --qos, --participant, --pki and --identity to a CLI11 app.
void add_dds_flags(CLI::App& app, DdsFlags& flags);

// Applies environment and defaults (`default_identity`: the program's own identity). Throws
// std::invalid_argument naming the flag or variable (domain outside 0..232, unreadable QoS
// file, a PKI directory that is not one).
DdsOptions resolve_dds_options(const DdsFlags& flags, const std::string& default_identity = "");

// The QoS file used when neither flag nor environment names one.
std::string default_qos_file();

}  // namespace vcockpit
