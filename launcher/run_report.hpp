#pragma once
// The lesson's score at the end of a rig run: as JSON for summary.json ("procedures"), and as a
// printable report page, OUT/report.html (one self-contained file: each procedure's steps with
// their times and errors, and a timeline of the run), with OUT/report.png drawn from it by
// headless Chromium when it is installed (scripts/setup installs it); without it the page alone.

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "launcher/rig_monitor.hpp"

namespace vcockpit::rig {

struct RunSummary;

// {"lesson", "started", "complete", "errors", "list": [...]}; null without a lesson.
nlohmann::ordered_json procedures_json(const std::vector<SeenProcedure>& procedures);

// The report page's HTML.
std::string report_html(const RunSummary& summary);
// Writes OUT/report.html (atomically) and, when `chromium` exists, OUT/report.png (bounded: 60 s,
// loopback only). Returns what was written, for the log; throws FileError for the HTML only.
std::string write_report(const RunSummary& summary, const std::string& out_dir,
                         const std::string& chromium = "/usr/bin/chromium");

}  // namespace vcockpit::rig
