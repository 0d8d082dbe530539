#pragma once
// Which /dev/shm entries are Fast DDS's: its shared-memory segments, data-sharing pools and their
// semaphores. A node killed with kill -9 leaves these behind (the launcher removes the ones its
// run left; the tests check they leave none); anything else there belongs to other programs.

#include <string_view>

namespace vcockpit {

inline bool is_fast_dds_shm_name(std::string_view name) {
  for (std::string_view prefix : {"fastrtps_", "sem.fastrtps_", "fast_datasharing_",
                                  "sem.fast_datasharing_"}) {
    if (name.substr(0, prefix.size()) == prefix) return true;
  }
  return false;
}

}  // namespace vcockpit
