#pragma once
// Degraded rows to a glove log: valid rows in the canonical columns, dropouts as all-`nan` rows.
// Written atomically (GloveLogWriter): a failure leaves no file under the name.

#include <string>
#include <vector>

#include "glove_driver/degrade/data_loss.hpp"

namespace vcockpit::degrade {

// Throws hand::GloveLogError on I/O failure.
void write_degraded_log(const std::string& path, const std::vector<DegradedRow>& rows,
                        bool left_hand, const std::vector<std::string>& comments);

}  // namespace vcockpit::degrade
