#include "instructor/station_server.hpp"

#include <httplib.h>
#include <spdlog/spdlog.h>

#include "common/clock.hpp"

namespace vcockpit::instructor {
namespace {

constexpr std::size_t kMaxBody = 4096;

void reply_json(httplib::Response& res, const nlohmann::json& j, int status = 200) {
  res.status = status;
  res.set_header("Cache-Control", "no-store");
  res.set_content(j.dump(), "application/json");
}

void reply_error(httplib::Response& res, const std::string& why) {
  reply_json(res, {{"error", why}}, 400);
}

}  // namespace

bool parse_sim_command(const std::string& word, cockpit::SimCommandKind& kind) {
  for (const cockpit::SimCommandKind k :
       {cockpit::FREEZE, cockpit::UNFREEZE, cockpit::RESET_TO_START, cockpit::SAVE_CHECKPOINT,
        cockpit::RESET_TO_CHECKPOINT, cockpit::RESTART_REPLAY}) {
    if (word == sim_command_word(k)) {
      kind = k;
      return true;
    }
  }
  return false;
}

StationServer::StationServer(StationModel& model, StationLink& link, const std::string& web_dir)
    : model_(model), link_(link), server_(std::make_unique<httplib::Server>()) {
  if (!server_->set_mount_point("/", web_dir))
    throw std::runtime_error("the station's web page directory " + web_dir + " does not exist");
  server_->set_payload_max_length(kMaxBody);
  routes();
}

StationServer::~StationServer() = default;

void StationServer::routes() {
  server_->Get("/api/state", [this](const httplib::Request&, httplib::Response& res) {
    reply_json(res, model_.state_json(monotonic_now_ns()));
  });
  server_->Get("/api/events", [this](const httplib::Request& req, httplib::Response& res) {
    int64_t after = -1;
    if (req.has_param("after")) {
      const std::string text = req.get_param_value("after");
      try {
        std::size_t used = 0;
        after = std::stoll(text, &used);
        if (used != text.size()) throw std::invalid_argument(text);
      } catch (const std::exception&) {
        reply_error(res, "after: not an integer: '" + text + "'");
        return;
      }
    }
    reply_json(res, model_.events_json(after));
  });
  server_->Get("/view.png", [this](const httplib::Request&, httplib::Response& res) {
    std::string png;
    if (!model_.view_png(png)) {
      res.status = 503;
      res.set_header("Cache-Control", "no-store");
      res.set_content("no picture of the pilot's view yet", "text/plain");
      return;
    }
    res.set_header("Cache-Control", "no-store");
    res.set_content(std::move(png), "image/png");
  });
  server_->Post("/api/sim", [this](const httplib::Request& req, httplib::Response& res) {
    const nlohmann::json body = nlohmann::json::parse(req.body, nullptr, false);
    if (!body.is_object() || !body.contains("command") || !body["command"].is_string()) {
      reply_error(res, "expected {\"command\": \"freeze\" | \"unfreeze\" | \"reset_start\" | "
                       "\"save_checkpoint\" | \"reset_checkpoint\" | \"restart_replay\"}");
      return;
    }
    cockpit::SimCommandKind kind{};
    const std::string word = body["command"].get<std::string>();
    if (!parse_sim_command(word, kind)) {
      reply_error(res, "command: unknown '" + word + "'");
      return;
    }
    std::string checkpoint = "default";
    if (body.contains("checkpoint")) {
      if (!body["checkpoint"].is_string() || body["checkpoint"].get<std::string>().empty() ||
          body["checkpoint"].get<std::string>().size() > 64) {
        reply_error(res, "checkpoint: a name of 1 to 64 characters");
        return;
      }
      checkpoint = body["checkpoint"].get<std::string>();
    }
    const int64_t seq = link_.send_sim(kind, checkpoint);
    if (seq < 0) {
      reply_json(res, {{"error", "the command could not be sent"}}, 503);
      return;
    }
    model_.on_command_sent("SENT " + word +
                           (kind == cockpit::SAVE_CHECKPOINT || kind == cockpit::RESET_TO_CHECKPOINT
                                ? " '" + checkpoint + "'"
                                : std::string()) +
                           " (#" + std::to_string(seq) + ")");
    spdlog::info("sim command #{}: {}", seq, word);
    reply_json(res, {{"seq", seq}});
  });
  server_->Post("/api/control", [this](const httplib::Request& req, httplib::Response& res) {
    const nlohmann::json body = nlohmann::json::parse(req.body, nullptr, false);
    if (!body.is_object() || !body.contains("control_id") || !body.contains("position") ||
        !body["control_id"].is_number_unsigned() || !body["position"].is_number_unsigned()) {
      reply_error(res, "expected {\"control_id\": C, \"position\": P} (non-negative integers)");
      return;
    }
    const uint64_t control = body["control_id"].get<uint64_t>();
    const uint64_t position = body["position"].get<uint64_t>();
    if (control > UINT32_MAX || position > UINT32_MAX ||
        !model_.has_control_position(static_cast<uint32_t>(control), static_cast<uint32_t>(position))) {
      reply_error(res, "no control " + std::to_string(control) + " with a position " +
                           std::to_string(position));
      return;
    }
    const int64_t seq = link_.send_control(static_cast<uint32_t>(control), static_cast<uint32_t>(position));
    if (seq < 0) {
      reply_json(res, {{"error", "the command could not be sent"}}, 503);
      return;
    }
    spdlog::info("control command #{}: control {} to position {}", seq, control, position);
    reply_json(res, {{"seq", seq}});
  });
  server_->Post("/api/failure", [this](const httplib::Request& req, httplib::Response& res) {
    const nlohmann::json body = nlohmann::json::parse(req.body, nullptr, false);
    if (!body.is_object() || !body.contains("failure") || !body["failure"].is_string() ||
        !body.contains("inserted") || !body["inserted"].is_boolean()) {
      reply_error(res, "expected {\"failure\": NAME, \"inserted\": true | false}");
      return;
    }
    const std::string failure = body["failure"].get<std::string>();
    const bool inserted = body["inserted"].get<bool>();
    if (!model_.knows_failures()) {
      reply_json(res, {{"error", "no systems node has said which failures it has"}}, 503);
      return;
    }
    if (!model_.has_failure(failure)) {
      reply_error(res, "failure: unknown '" + failure + "'");
      return;
    }
    const int64_t seq = link_.send_failure(failure, inserted);
    if (seq < 0) {
      reply_json(res, {{"error", "the command could not be sent"}}, 503);
      return;
    }
    model_.on_command_sent("SENT " + std::string(inserted ? "insert " : "clear ") + failure +
                           " (#" + std::to_string(seq) + ")");
    spdlog::info("failure command #{}: {} {}", seq, inserted ? "insert" : "clear", failure);
    reply_json(res, {{"seq", seq}});
  });
  server_->set_exception_handler([](const httplib::Request& req, httplib::Response& res,
                                    std::exception_ptr ep) {
    std::string what = "unknown";
    try {
      std::rethrow_exception(ep);
    } catch (const std::exception& e) {
      what = e.what();
    } catch (...) {
    }
    spdlog::warn("{} {}: {}", req.method, req.path, what);
    res.status = 500;
    res.set_content(nlohmann::json{{"error", what}}.dump(), "application/json");
  });
}

int StationServer::bind(const std::string& host, int port, std::string& error) {
  if (port == 0) {
    const int bound = server_->bind_to_any_port(host);
    if (bound <= 0) error = "cannot listen on " + host + " (any port)";
    return bound > 0 ? bound : -1;
  }
  if (!server_->bind_to_port(host, port)) {
    error = "cannot listen on " + host + ":" + std::to_string(port) +
            " (in use by another program? choose another with --port)";
    return -1;
  }
  return port;
}

void StationServer::serve() { server_->listen_after_bind(); }
void StationServer::stop() { server_->stop(); }

}  // namespace vcockpit::instructor
