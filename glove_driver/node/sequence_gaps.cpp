#include "glove_driver/node/sequence_gaps.hpp"

namespace vcockpit::glove {

bool SequenceGaps::add(const WriterId& writer, uint64_t sequence) {
  auto [it, first] = newest_.try_emplace(writer, Track{sequence, 0});
  if (first) return true;
  Track& track = it->second;
  if (sequence <= track.newest) {
    ++duplicates_;
    return false;
  }
  const uint64_t gap = sequence - track.newest - 1;
  track.missing += gap;
  missing_ += gap;
  track.newest = sequence;
  return true;
}

uint64_t SequenceGaps::missing_of(const WriterId& writer) const {
  const auto it = newest_.find(writer);
  return it == newest_.end() ? 0 : it->second.missing;
}

}  // namespace vcockpit::glove
