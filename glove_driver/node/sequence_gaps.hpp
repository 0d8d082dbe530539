#pragma once
// Sequence gaps per writer: what a recorder never received of what its writers sent. Each DDS
// writer numbers its samples 1, 2, 3, ... (RTPS sequence numbers, whatever the vendor), so
// - a writer's first sample seen numbered n means n - 1 were sent before the recorder matched it
//   (or before their repair window closed): missed at the start;
// - a jump from n to m > n + 1 means m - n - 1 samples were lost on the way (or overwritten in a
//   history before they were read): missed in gaps.
// Both are missing: a recording has every sample its writers sent, or says how many it lacks.

#include <array>
#include <cstdint>
#include <map>

namespace vcockpit::glove {

using WriterId = std::array<uint8_t, 16>;  // the writer's GUID (DDS instance handle)

class SequenceGaps {
 public:
  struct Track {
    uint64_t first = 0;     // the first sequence number seen
    uint64_t newest = 0;
    uint64_t in_gaps = 0;   // missing between the first and the newest
    uint64_t at_start() const { return first - 1; }  // sent before the first seen
    uint64_t missing() const { return at_start() + in_gaps; }
  };

  // False for a sample already seen or older than the newest one of its writer (not to be
  // written again); true otherwise, after counting what is missing before it.
  bool add(const WriterId& writer, uint64_t sequence);

  uint64_t duplicates() const { return duplicates_; }
  std::size_t writers() const { return tracks_.size(); }
  // The writer's counts; all zero for a writer never seen.
  Track of(const WriterId& writer) const;

 private:
  std::map<WriterId, Track> tracks_;
  uint64_t duplicates_ = 0;
};

}  // namespace vcockpit::glove
