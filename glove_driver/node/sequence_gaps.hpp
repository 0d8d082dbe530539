#pragma once
// Sequence gaps per writer: what a recorder never received of what its writers sent. Each DDS
// writer numbers its samples 1, 2, 3, ... (RTPS sequence numbers, whatever the vendor); a jump
// from n to m > n + 1 means m - n - 1 samples were lost on the way (or overwritten in a history
// before they were read). Counting starts at the first sample seen from each writer: what a
// writer sent before the recorder matched it is not missing.

#include <array>
#include <cstdint>
#include <map>

namespace vcockpit::glove {

using WriterId = std::array<uint8_t, 16>;  // the writer's GUID (DDS instance handle)

class SequenceGaps {
 public:
  // False for a sample already seen or older than the newest one of its writer (not to be
  // written again); true otherwise, after counting the gap before it.
  bool add(const WriterId& writer, uint64_t sequence);

  uint64_t missing() const { return missing_; }
  uint64_t duplicates() const { return duplicates_; }
  std::size_t writers() const { return newest_.size(); }
  uint64_t missing_of(const WriterId& writer) const;

 private:
  struct Track {
    uint64_t newest = 0;
    uint64_t missing = 0;
  };
  std::map<WriterId, Track> newest_;
  uint64_t missing_ = 0;
  uint64_t duplicates_ = 0;
};

}  // namespace vcockpit::glove
