#include "glove_driver/degrade/data_loss.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/assert.hpp"
#include "glove_driver/degrade/degrade_error.hpp"
#include "glove_driver/degrade/seeded_random.hpp"

namespace vcockpit::degrade {
namespace {

bool overlaps(const PlacedGap& a, const PlacedGap& b) {
  return a.start_ns < b.start_ns + b.length_ns && b.start_ns < a.start_ns + a.length_ns;
}

std::string seconds_text(int64_t ns) { return std::to_string(static_cast<double>(ns) * 1e-9); }

}  // namespace

std::vector<PlacedGap> cut_gaps(std::vector<hand::GloveSample>& samples, const Gaps& gaps,
                                uint64_t seed) {
  if (samples.empty() || (gaps.count == 0 && gaps.at_s.empty())) return {};
  if (!(gaps.min_s > 0) || gaps.max_s < gaps.min_s) {
    throw DegradeError("gap lengths need 0 < min <= max, got " + std::to_string(gaps.min_s) +
                       ".." + std::to_string(gaps.max_s) + " s");
  }
  SeededRandom random(seed, "gaps");
  const int64_t first_ns = samples.front().t_ns;
  const int64_t last_ns = samples.back().t_ns;
  // strictly inside: the first and the last row stay
  auto fits = [&](const PlacedGap& g) {
    return g.start_ns > first_ns && g.start_ns + g.length_ns <= last_ns;
  };
  std::vector<PlacedGap> placed;
  auto place = [&](PlacedGap g) {
    for (const PlacedGap& other : placed) {
      if (overlaps(g, other)) return false;
    }
    placed.push_back(g);
    return true;
  };
  const int wanted = gaps.at_s.empty() ? gaps.count : static_cast<int>(gaps.at_s.size());
  for (int i = 0; i < wanted; ++i) {
    const int64_t length_ns = std::llround(random.uniform(gaps.min_s, gaps.max_s) * 1e9);
    if (!gaps.at_s.empty()) {
      const PlacedGap g{first_ns + std::llround(gaps.at_s[static_cast<std::size_t>(i)] * 1e9),
                        length_ns};
      if (!fits(g)) {
        throw DegradeError("a gap at " + std::to_string(gaps.at_s[static_cast<std::size_t>(i)]) +
                           " s of " + seconds_text(length_ns) + " s does not fit inside the log (" +
                           seconds_text(last_ns - first_ns) + " s)");
      }
      if (!place(g)) {
        throw DegradeError("the gap at " + std::to_string(gaps.at_s[static_cast<std::size_t>(i)]) +
                           " s overlaps another");
      }
      continue;
    }
    const int64_t room_ns = last_ns - first_ns - length_ns - 1;
    bool done = false;
    for (int attempt = 0; attempt < 1000 && room_ns > 0 && !done; ++attempt) {
      const PlacedGap g{first_ns + 1 + static_cast<int64_t>(random.below(
                                           static_cast<uint64_t>(room_ns))),
                        length_ns};
      done = fits(g) && place(g);
    }
    if (!done) {
      throw DegradeError("cannot place " + std::to_string(gaps.count) + " gaps of up to " +
                         std::to_string(gaps.max_s) + " s apart in a log of " +
                         seconds_text(last_ns - first_ns) + " s");
    }
  }
  std::sort(placed.begin(), placed.end(),
            [](const PlacedGap& a, const PlacedGap& b) { return a.start_ns < b.start_ns; });
  std::erase_if(samples, [&](const hand::GloveSample& s) {
    for (const PlacedGap& g : placed) {
      if (s.t_ns >= g.start_ns && s.t_ns < g.start_ns + g.length_ns) return true;
    }
    return false;
  });
  return placed;
}

std::vector<DegradedRow> mark_dropouts(const std::vector<hand::GloveSample>& samples, double rate,
                                       uint64_t seed) {
  VCOCKPIT_ASSERT(rate >= 0 && rate < 1, "mark_dropouts: rate in [0, 1)");
  std::vector<DegradedRow> rows;
  rows.reserve(samples.size());
  for (const hand::GloveSample& s : samples) rows.push_back({s, true});
  if (rows.size() < 2) return rows;
  // exactly k of rows 1..n-1: the first k of a seeded partial Fisher-Yates shuffle
  const std::size_t candidates = rows.size() - 1;
  const auto k = static_cast<std::size_t>(std::llround(rate * static_cast<double>(candidates)));
  std::vector<std::size_t> index(candidates);
  for (std::size_t i = 0; i < candidates; ++i) index[i] = i + 1;
  SeededRandom random(seed, "dropouts");
  for (std::size_t i = 0; i < k; ++i) {
    const std::size_t j = i + static_cast<std::size_t>(random.below(candidates - i));
    std::swap(index[i], index[j]);
    rows[index[i]].valid = false;
  }
  return rows;
}

}  // namespace vcockpit::degrade
