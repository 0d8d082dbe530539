// rig.yaml (launcher/rig_config.cpp): any text is either a rig or a ConfigError. The loader takes
// a path and checks the qos file beside it, so each input is written to a scratch directory that
// holds a qos.xml.

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "common/yaml_config.hpp"
#include "fuzz/fuzz_support.hpp"
#include "launcher/rig_config.hpp"

namespace {

namespace fs = std::filesystem;

// One directory for every run (libFuzzer leaves without running atexit handlers); each process
// writes its own file there and removes it after each input.
const fs::path& scratch_dir() {
  static const fs::path dir = [] {
    fs::path d = fs::temp_directory_path() / "vcockpit_fuzz_rig";
    fs::create_directories(d);
    std::ofstream(d / "qos.xml") << "<dds/>\n";
    return d;
  }();
  return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  using namespace vcockpit;
  const fs::path path = scratch_dir() / ("rig_" + std::to_string(getpid()) + ".yaml");
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  try {
    rig::RigConfig config = rig::load_rig_config(path.string());
    config.ui_port = 8080;
    config.start_at_ns = 1;
    for (const rig::NodeSpec& node : config.nodes) {
      rig::node_starts(node, config);
      rig::expand_command(node, config, "/tmp/out");
    }
  } catch (const ConfigError&) {
  }
  fs::remove(path);
  return 0;
}
