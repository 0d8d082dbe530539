// instructor_station: the instructor's operating station in a browser. Serves one page on
// http://127.0.0.1:PORT/ (loopback; --lan opens it to every interface): the pilot's view, every
// node's status, grasp, control and sim events as they happen, the controls' positions, and
// buttons that freeze, reset and restart the simulation and set controls (station_server.hpp).

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <thread>

#include "common/clock.hpp"
#include "common/logging.hpp"
#include "common/signals.hpp"
#include "instructor/station_link.hpp"
#include "instructor/station_model.hpp"
#include "instructor/station_server.hpp"

int main(int argc, char** argv) {
  using namespace vcockpit;
  CLI::App app("instructor_station: the instructor's operating station, one web page");
  DdsFlags dds_flags;
  int port = 8077;
  bool lan = false;
  std::string web_dir = VCOCKPIT_WEB_DIR;
  std::string node_name = "instructor_station";
  std::string log_level = "info";
  app.add_option("--port", port, "TCP port of the page (0: any free port)")
      ->check(CLI::Range(0, 65535))
      ->capture_default_str();
  app.add_flag("--lan", lan, "listen on every interface, not only loopback (anyone on the network "
                             "can then freeze the simulation and set controls)");
  app.add_option("--web-dir", web_dir, "the page's files")->check(CLI::ExistingDirectory)
      ->capture_default_str();
  app.add_option("--node-name", node_name, "name on the commands it sends")->capture_default_str();
  add_dds_flags(app, dds_flags);
  app.add_option("--log-level", log_level, "trace, debug, info, warn, error")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  try {
    setup_logging("instructor_station", log_level);
    install_shutdown_handlers();
    DdsParticipant participant(resolve_dds_options(dds_flags, "instructor_station"), node_name);
    instructor::StationModel model;
    instructor::StationLink link(participant, model, node_name);
    instructor::StationServer server(model, link, web_dir);
    const std::string host = lan ? "0.0.0.0" : "127.0.0.1";
    std::string error;
    const int bound = server.bind(host, port, error);
    if (bound < 0) {
      spdlog::error("{}", error);
      return 1;
    }
    std::thread http([&server] { server.serve(); });
    spdlog::info("instructor station on http://{}:{}/ (domain {})", lan ? "0.0.0.0" : "127.0.0.1",
                 bound, participant.domain_id());
    if (lan) spdlog::warn("--lan: the station answers on every interface");
    while (!shutdown_requested()) {
      link.poll();
      sleep_until_ns(monotonic_now_ns() + 20'000'000);
    }
    server.stop();
    http.join();
    spdlog::info("stopped");
    return 0;
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
}
