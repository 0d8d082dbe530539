#include "launcher/run_report.hpp"

#include <spdlog/spdlog.h>
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "common/atomic_file.hpp"
#include "common/clock.hpp"
#include "launcher/run_summary.hpp"

namespace vcockpit::rig {
namespace {

std::string escaped(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string fixed(double v, int digits) {
  char text[32];
  std::snprintf(text, sizeof text, "%.*f", digits, v);
  return text;
}

std::string flags_of(const SeenProcedure::Step& st) {
  std::string f;
  if (st.out_of_order) f += "out of order ";
  if (st.late) f += "late ";
  if (st.undone) f += "undone ";
  if (!f.empty()) f.pop_back();
  return f;
}

// The timeline: one lane per procedure (its span, each step done as a tick at its time, a
// missed step as a cross at the end) and one for the controls and failures.
std::string timeline_svg(const RunSummary& s) {
  double end_s = 1.0;
  for (const SeenProcedure& p : s.procedures) end_s = std::max({end_s, p.ended_s, p.started_s});
  for (const SeenControlEvent& e : s.control_events) end_s = std::max(end_s, e.t_s);
  for (const SeenSystemsEvent& e : s.systems_events) end_s = std::max(end_s, e.t_s);
  end_s = std::ceil(end_s / 10.0) * 10.0;
  const double left = 170, width = 900, lane = 34, top = 24;
  const int lanes = static_cast<int>(s.procedures.size()) + 1;
  const double height = top + lane * lanes + 24;
  const auto x = [&](double t) { return left + width * std::clamp(t / end_s, 0.0, 1.0); };
  std::ostringstream o;
  o << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << left + width + 30 << "\" height=\""
    << height << "\" font-family=\"sans-serif\" font-size=\"12\">";
  for (double t = 0; t <= end_s + 1e-9; t += 10.0) {
    o << "<line x1=\"" << x(t) << "\" y1=\"" << top - 6 << "\" x2=\"" << x(t) << "\" y2=\""
      << height - 20 << "\" stroke=\"#ddd\"/><text x=\"" << x(t) << "\" y=\"" << height - 6
      << "\" text-anchor=\"middle\" fill=\"#555\">" << fixed(t, 0) << " s</text>";
  }
  int row = 0;
  for (const SeenProcedure& p : s.procedures) {
    const double y = top + lane * row++ + lane / 2;
    o << "<text x=\"4\" y=\"" << y + 4 << "\" fill=\"#222\">" << escaped(p.title) << "</text>";
    if (p.started_s >= 0) {
      const double e = p.ended_s >= 0 ? p.ended_s : end_s;
      const char* colour = p.state == "complete" ? "#cfe8d2" : p.state == "incomplete" ? "#f6d0d0" : "#d6e4f5";
      o << "<rect x=\"" << x(p.started_s) << "\" y=\"" << y - 9 << "\" width=\""
        << std::max(2.0, x(e) - x(p.started_s)) << "\" height=\"18\" fill=\"" << colour << "\"/>";
    }
    for (const SeenProcedure::Step& st : p.steps) {
      if (st.status == "done" && st.done_s >= 0) {
        const char* colour = flags_of(st).empty() ? "#1f8a3a" : "#e08600";
        o << "<line x1=\"" << x(st.done_s) << "\" y1=\"" << y - 9 << "\" x2=\"" << x(st.done_s)
          << "\" y2=\"" << y + 9 << "\" stroke=\"" << colour << "\" stroke-width=\"3\"><title>"
          << escaped(st.item + ": " + st.action + " at " + fixed(st.done_s, 2) + " s") << "</title></line>";
      } else if (st.status == "missed" && p.ended_s >= 0) {
        o << "<text x=\"" << x(p.ended_s) << "\" y=\"" << y + 5 << "\" fill=\"#c62828\" "
          << "text-anchor=\"middle\" font-weight=\"bold\">&#x2715;<title>"
          << escaped(st.item + ": " + st.action + " missed") << "</title></text>";
      }
    }
  }
  const double y = top + lane * row + lane / 2;
  o << "<text x=\"4\" y=\"" << y + 4 << "\" fill=\"#222\">controls, failures</text>";
  for (const SeenControlEvent& e : s.control_events) {
    o << "<line x1=\"" << x(e.t_s) << "\" y1=\"" << y - 7 << "\" x2=\"" << x(e.t_s) << "\" y2=\""
      << y + 7 << "\" stroke=\"#555\"><title>" << escaped(e.control + " " + e.from + " -> " + e.to)
      << "</title></line>";
  }
  for (const SeenSystemsEvent& e : s.systems_events) {
    if (e.kind == "changed") continue;
    o << "<circle cx=\"" << x(e.t_s) << "\" cy=\"" << y << "\" r=\"5\" fill=\""
      << (e.kind == "failure_inserted" ? "#c62828" : "#1f8a3a") << "\"><title>"
      << escaped(e.name + (e.kind == "failure_inserted" ? " inserted" : " cleared")) << "</title></circle>";
  }
  o << "</svg>";
  return o.str();
}

}  // namespace

nlohmann::ordered_json procedures_json(const std::vector<SeenProcedure>& procedures) {
  if (procedures.empty()) return nullptr;
  const auto time = [](double s) { return s < 0 ? nlohmann::ordered_json() : nlohmann::ordered_json(s); };
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  int started = 0, complete = 0, errors = 0;
  for (const SeenProcedure& p : procedures) {
    nlohmann::ordered_json steps = nlohmann::ordered_json::array();
    for (const SeenProcedure::Step& st : p.steps) {
      steps.push_back({{"item", st.item}, {"action", st.action}, {"status", st.status},
                       {"done_s", time(st.done_s)}, {"since_previous_s", time(st.since_previous_s)},
                       {"out_of_order", st.out_of_order}, {"late", st.late}, {"undone", st.undone}});
    }
    list.push_back({{"name", p.name}, {"title", p.title}, {"state", p.state},
                    {"started_s", time(p.started_s)}, {"ended_s", time(p.ended_s)},
                    {"errors", p.errors}, {"steps", steps}});
    started += p.state != "waiting" ? 1 : 0;
    complete += p.state == "complete" ? 1 : 0;
    errors += static_cast<int>(p.errors);
  }
  return {{"lesson", procedures.front().lesson}, {"started", started}, {"complete", complete},
          {"errors", errors}, {"list", list}};
}

std::string report_html(const RunSummary& s) {
  std::ostringstream o;
  int complete = 0, started = 0, errors = 0;
  for (const SeenProcedure& p : s.procedures) {
    complete += p.state == "complete" ? 1 : 0;
    started += p.state != "waiting" ? 1 : 0;
    errors += static_cast<int>(p.errors);
  }
  const std::string lesson = s.procedures.empty() ? "" : s.procedures.front().lesson;
  o << "<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>vcockpit report: "
    << escaped(lesson) << "</title><style>"
    << "body{font-family:sans-serif;margin:24px;color:#222;max-width:1120px}"
    << "h1{font-size:22px;margin:0}h2{font-size:17px;margin:22px 0 6px}"
    << ".sub{color:#666;font-size:13px}table{border-collapse:collapse;width:100%;font-size:13px}"
    << "th,td{border-bottom:1px solid #ddd;padding:3px 6px;text-align:left}"
    << "td.num{text-align:right;font-variant-numeric:tabular-nums}"
    << ".complete{color:#1f8a3a}.incomplete,.missed{color:#c62828}.waiting{color:#777}"
    << ".running{color:#2f6fb3}.flag{color:#e08600;font-weight:bold}"
    << ".total{font-size:16px;margin:8px 0}</style></head><body>\n";
  o << "<h1>" << escaped(lesson) << "</h1>\n<div class=\"sub\">vcockpit rig " << escaped(s.rig_path)
    << " &middot; glove log " << escaped(s.log_path) << " &middot; " << fixed(s.wall_s, 1)
    << " s of wall time</div>\n";
  o << "<div class=\"total\" id=\"total\" data-complete=\"" << complete << "\" data-errors=\""
    << errors << "\">" << complete << " of " << started << " procedure" << (started == 1 ? "" : "s")
    << " flown complete, " << errors << " error" << (errors == 1 ? "" : "s") << "</div>\n";
  o << "<h2>Timeline</h2>\n" << timeline_svg(s) << "\n";
  for (const SeenProcedure& p : s.procedures) {
    o << "<h2 class=\"procedure\" data-name=\"" << escaped(p.name) << "\" data-state=\"" << p.state
      << "\">" << escaped(p.title) << " <span class=\"" << p.state << "\">" << p.state << "</span>";
    if (p.state != "waiting") {
      o << " <span class=\"sub\">" << p.errors << " error" << (p.errors == 1 ? "" : "s");
      if (p.started_s >= 0 && p.ended_s >= 0)
        o << ", " << fixed(p.ended_s - p.started_s, 2) << " s (from " << fixed(p.started_s, 2)
          << " to " << fixed(p.ended_s, 2) << " s)";
      o << "</span>";
    } else {
      o << " <span class=\"sub\">not started: no error</span>";
    }
    o << "</h2>\n<table><tr><th>#</th><th>item</th><th>action</th><th>status</th>"
      << "<th class=\"num\">done at</th><th class=\"num\">after the previous</th><th>errors</th></tr>\n";
    for (std::size_t i = 0; i < p.steps.size(); ++i) {
      const SeenProcedure::Step& st = p.steps[i];
      o << "<tr><td>" << i + 1 << "</td><td>" << escaped(st.item) << "</td><td>"
        << escaped(st.action) << "</td><td class=\"" << st.status << "\">" << st.status
        << "</td><td class=\"num\">" << (st.done_s >= 0 ? fixed(st.done_s, 2) + " s" : "")
        << "</td><td class=\"num\">"
        << (st.since_previous_s >= 0 ? "+" + fixed(st.since_previous_s, 2) + " s" : "")
        << "</td><td class=\"flag\">" << escaped(flags_of(st)) << "</td></tr>\n";
    }
    o << "</table>\n";
  }
  o << "</body></html>\n";
  return o.str();
}

std::string write_report(const RunSummary& s, const std::string& out_dir, const std::string& chromium) {
  const std::string html_path = out_dir + "/report.html";
  const std::string png_path = out_dir + "/report.png";
  {
    AtomicFile html(html_path);
    html.write(report_html(s));
    html.commit();
  }
  std::error_code ignored;
  std::filesystem::remove(png_path, ignored);
  if (!std::filesystem::exists(chromium)) return html_path + " (no " + chromium + " for the PNG)";
  // headless Chromium draws the page into a PNG: loopback only (its proxy points at a closed
  // port, no name resolves), a profile of its own, at most 60 s
  const std::string profile = out_dir + "/.report-profile";
  const std::string partial = png_path + ".partial.png";
  int height = 420;
  for (const SeenProcedure& p : s.procedures) height += 90 + 26 * static_cast<int>(p.steps.size());
  std::vector<std::string> args = {
      chromium, "--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
      "--hide-scrollbars", "--force-device-scale-factor=1", "--no-first-run",
      "--disable-extensions", "--disable-background-networking", "--disable-component-update",
      "--disable-sync", "--disable-default-apps", "--no-default-browser-check",
      "--disable-domain-reliability", "--disable-breakpad", "--no-pings",
      "--proxy-server=http://127.0.0.1:9", "--host-resolver-rules=MAP * ~NOTFOUND",
      "--user-data-dir=" + profile, "--window-size=1180," + std::to_string(height),
      "--screenshot=" + partial, "file://" + std::filesystem::absolute(html_path).string()};
  // everything the child needs is made before fork(): the launcher has DDS threads, and after
  // fork only async-signal-safe calls are safe
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    setpgid(0, 0);
    const int null = ::open("/dev/null", O_WRONLY);
    if (null >= 0) {
      dup2(null, STDOUT_FILENO);
      dup2(null, STDERR_FILENO);
    }
    // none of the launcher's files and sockets (DDS, logs) go with it
    for (int fd = 3; fd < 1024; ++fd) ::close(fd);
    execv(argv[0], argv.data());
    _exit(127);
  }
  if (pid > 0) setpgid(pid, pid);  // the group exists before the parent may signal it
  std::string result = html_path;
  if (pid < 0) return result + " (the PNG: cannot start " + chromium + ")";
  int status = 0;
  const int64_t deadline = monotonic_now_ns() + 60'000'000'000;
  bool done = false;
  while (!done && monotonic_now_ns() < deadline) {
    const pid_t r = waitpid(pid, &status, WNOHANG);
    if (r == pid) done = true;
    else sleep_until_ns(monotonic_now_ns() + 50'000'000);
  }
  // Chromium's helper processes share its group: none outlives the report
  kill(-pid, SIGKILL);
  if (!done) waitpid(pid, &status, 0);
  std::filesystem::remove_all(profile, ignored);
  if (done && WIFEXITED(status) && WEXITSTATUS(status) == 0 && std::filesystem::exists(partial)) {
    std::filesystem::rename(partial, png_path, ignored);
    if (!ignored) return result + ", " + png_path;
  }
  std::filesystem::remove(partial, ignored);
  return result + " (the PNG: " + chromium + (done ? " failed" : " took over 60 s") + ")";
}

}  // namespace vcockpit::rig
