#pragma once
// The instructor station's web server (cpp-httplib): the page from the project's
// instructor/web, and a small JSON API over the StationModel and the StationLink:
//   GET  /api/state            the rig now (nodes, sim time, frozen, hands, controls, view)
//   GET  /api/events?after=K   grasp, control and sim events after seq K (-1: the newest)
//   GET  /view.png             the newest preview of the pilot's left-eye view (503: none yet)
//   POST /api/sim              {"command": "freeze" | "unfreeze" | "reset_start" |
//                               "save_checkpoint" | "reset_checkpoint" | "restart_replay",
//                               "checkpoint": "name"}                     -> {"seq": N}
//   POST /api/control          {"control_id": C, "position": P}           -> {"seq": N}
// Bad requests get 400 with {"error": why}. Loopback only unless the station is opened to the
// LAN; request bodies are capped.

#include <memory>
#include <string>

#include "instructor/station_link.hpp"
#include "instructor/station_model.hpp"

namespace httplib {
class Server;
}

namespace vcockpit::instructor {

class StationServer {
 public:
  StationServer(StationModel& model, StationLink& link, const std::string& web_dir);
  ~StationServer();
  StationServer(const StationServer&) = delete;
  StationServer& operator=(const StationServer&) = delete;

  // Binds host:port (port 0: any free port); returns the port, or -1 with why in `error`.
  int bind(const std::string& host, int port, std::string& error);
  // Serves until stop() (blocks; run it on its own thread).
  void serve();
  void stop();

 private:
  void routes();

  StationModel& model_;
  StationLink& link_;
  std::unique_ptr<httplib::Server> server_;
};

// "freeze" -> FREEZE, ...; false for a word that is none of them.
bool parse_sim_command(const std::string& word, cockpit::SimCommandKind& kind);

}  // namespace vcockpit::instructor
