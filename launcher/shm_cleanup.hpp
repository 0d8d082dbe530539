#pragma once
// The /dev/shm files a rig run leaves: Fast DDS's shared-memory segments and semaphores of a node
// killed before it could remove them. Listed before the run; afterwards the DDS ones that appeared
// since are removed (anything that was already there belongs to someone else and stays).

#include <string>
#include <vector>

namespace vcockpit::rig {

// The names in /dev/shm, sorted (empty if it cannot be read).
std::vector<std::string> dev_shm_entries();

// Removes the Fast DDS files (fastrtps_*, fast_datasharing_* and their sem. twins) that are not
// in `before` (a dev_shm_entries() list). Returns how many were removed.
int remove_new_dds_shm(const std::vector<std::string>& before);

}  // namespace vcockpit::rig
