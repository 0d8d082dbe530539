#pragma once
// The report rig_launcher prints on stdout when a run is over: how it ended, the replayed
// samples, every grasp and release, frames and snapshots, the physics step rate, the
// glove-to-frame latency, and where the summary and logs are.

#include "launcher/run_summary.hpp"

namespace vcockpit::rig {

void print_console_report(const RunSummary& summary);

}  // namespace vcockpit::rig
