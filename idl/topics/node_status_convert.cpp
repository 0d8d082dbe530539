#include "idl/topics/node_status_convert.hpp"

namespace vcockpit {

void set_input_counts(const hand::InputCounts& c, cockpit::NodeStatus& status) {
  status.rejected(c.rejected());
  status.rejected_nonfinite(c.rejected_nonfinite);
  status.rejected_out_of_range(c.rejected_out_of_range);
  status.rejected_stale(c.rejected_stale);
  status.clamped(c.clamped);
  status.missing_columns(c.missing_columns);
  status.intervals(c.intervals);
  status.intervals_interpolated(c.intervals_interpolated);
  status.gaps_bridged(c.gaps_bridged);
  status.gaps_not_bridged(c.gaps_not_bridged);
  status.intervals_late(c.intervals_late);
  status.longest_interval_s(static_cast<double>(c.longest_interval_ns) * 1e-9);
  status.glove_lost(c.glove_lost);
}

}  // namespace vcockpit
