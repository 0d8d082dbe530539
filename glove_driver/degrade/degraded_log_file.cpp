#include "glove_driver/degrade/degraded_log_file.hpp"

#include "hand/glove_log.hpp"

namespace vcockpit::degrade {

void write_degraded_log(const std::string& path, const std::vector<DegradedRow>& rows,
                        bool left_hand, const std::vector<std::string>& comments) {
  hand::GloveLogWriter writer(path, left_hand, comments);
  for (const DegradedRow& row : rows) {
    if (row.valid) {
      writer.append(row.sample);
    } else {
      writer.append_dropout(row.sample.t_ns);
    }
  }
  writer.commit();
}

}  // namespace vcockpit::degrade
