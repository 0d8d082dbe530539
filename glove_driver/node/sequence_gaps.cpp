#include "glove_driver/node/sequence_gaps.hpp"

namespace vcockpit::glove {

bool SequenceGaps::add(const WriterId& writer, uint64_t sequence) {
  auto [it, first] = tracks_.try_emplace(writer, Track{sequence, sequence, 0});
  if (first) return true;
  Track& track = it->second;
  if (sequence <= track.newest) {
    ++duplicates_;
    return false;
  }
  track.in_gaps += sequence - track.newest - 1;
  track.newest = sequence;
  return true;
}

SequenceGaps::Track SequenceGaps::of(const WriterId& writer) const {
  const auto it = tracks_.find(writer);
  return it == tracks_.end() ? Track{1, 0, 0} : it->second;
}

}  // namespace vcockpit::glove
