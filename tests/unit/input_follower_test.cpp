// The real-time follower (physics_io/input_follower.hpp), against closed forms: a constant-
// velocity source at 33, 60, 120 and 1000 Hz is followed exactly (the shown hand is the source's
// hand `delay` ago, the delay one usual interval + the margin), arrival jitter within the margin
// makes no sample late, a gap over the max gap holds the hand, a delay of 0 holds the newest
// sample (no interpolation), and a new source starts afresh.

#include "physics_node/io/input_follower.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace vcockpit::physics_io {
namespace {

constexpr int64_t kMs = 1'000'000;
constexpr int64_t kTransit_ns = 150'000;             // source clock -> arrival
constexpr int64_t kStampBase_ns = 7'000'000'000;     // the source's stamp of its time 0
constexpr int64_t kArrivalBase_ns = 50'000'000'000;  // the local clock at the source's time 0
constexpr double kV_mps = 0.4;

hand::GloveSample at_source_time(int64_t t_ns) {
  hand::GloveSample s;
  s.t_ns = t_ns;
  s.p_MT_m = Eigen::Vector3d(kV_mps * static_cast<double>(t_ns) * 1e-9, 0.0, 1.0);
  s.joints_rad.fill(0.1);
  return s;
}

struct FollowRun {
  int64_t delay_ns = 0;
  double worst_lag_error_ns = 0;  // |shown lag - delay| over the steady part
  hand::InputCounts counts;
};

// Samples at `rate_hz` (arrival = stamp + transit + jitter), the follower asked every 1 ms.
FollowRun follow(double rate_hz, int64_t jitter_max_ns, const FollowerOptions& options,
                 double duration_s = 2.0) {
  InputFollower follower(options);
  std::mt19937 rng(7);
  std::uniform_int_distribution<int64_t> jitter(0, jitter_max_ns);
  const auto interval_ns = static_cast<int64_t>(std::llround(1e9 / rate_hz));
  const auto end_ns = static_cast<int64_t>(duration_s * 1e9);
  FollowRun run;
  int64_t next_k = 0;
  int64_t pending_arrival_ns = -1;
  hand::GloveSample pending;
  for (int64_t now = kArrivalBase_ns; now < kArrivalBase_ns + end_ns; now += kMs) {
    while (true) {
      if (pending_arrival_ns < 0) {
        pending = at_source_time(next_k * interval_ns);
        pending_arrival_ns = kArrivalBase_ns + pending.t_ns + kTransit_ns + jitter(rng);
        ++next_k;
      }
      if (pending_arrival_ns > now) break;
      follower.push(pending, pending_arrival_ns, kStampBase_ns + pending.t_ns);
      pending_arrival_ns = -1;
    }
    FollowedInput in;
    if (!follower.at(now, in)) continue;
    // constant velocity: the shown position says which source time is shown, exactly
    const double shown_t_ns = in.sample.p_MT_m.x() / kV_mps * 1e9;
    EXPECT_NEAR(shown_t_ns, static_cast<double>(in.sample.t_ns), 1.0);
    EXPECT_EQ(in.source_stamp_ns, kStampBase_ns + in.sample.t_ns);
    if (now - kArrivalBase_ns > 500 * kMs) {  // past the start and the delay's adaptation
      // lag behind the source's present (now - transit on the source clock)
      const double lag_ns = static_cast<double>(now - kArrivalBase_ns - kTransit_ns) - shown_t_ns;
      run.worst_lag_error_ns = std::max(
          run.worst_lag_error_ns, std::abs(lag_ns - static_cast<double>(follower.delay_ns())));
    }
  }
  run.delay_ns = follower.delay_ns();
  run.counts = follower.counts();
  return run;
}

TEST(InputFollower, ConstantVelocityIsFollowedExactlyOneIntervalPlusTheMarginBehind) {
  for (double rate_hz : {33.0, 60.0, 120.0, 1000.0}) {
    const FollowRun run = follow(rate_hz, 0, FollowerOptions{});
    const double interval_ns = 1e9 / rate_hz;
    EXPECT_NEAR(static_cast<double>(run.delay_ns), interval_ns + 2e6, 1.0) << rate_hz << " Hz";
    EXPECT_LT(run.worst_lag_error_ns, 2.0) << rate_hz << " Hz: the lag is exactly the delay";
    EXPECT_EQ(run.counts.intervals_late, 0u) << rate_hz << " Hz";
    EXPECT_EQ(run.counts.gaps_not_bridged, 0u);
    EXPECT_EQ(run.counts.intervals_interpolated, run.counts.intervals);
  }
}

TEST(InputFollower, ArrivalJitterWithinTheMarginMakesNoSampleLate) {
  for (double rate_hz : {33.0, 1000.0}) {
    const FollowRun run = follow(rate_hz, 1'500'000, FollowerOptions{});
    EXPECT_EQ(run.counts.intervals_late, 0u) << rate_hz << " Hz";
    // the offset is the fastest arrival, so the lag stays the delay plus at most the jitter
    EXPECT_LT(run.worst_lag_error_ns, 1.5e6 + 1.0) << rate_hz << " Hz";
  }
}

TEST(InputFollower, AFixedDelayIsKeptAndZeroHoldsTheNewestSample) {
  FollowerOptions fixed;
  fixed.fixed_delay_ns = 50 * kMs;
  const FollowRun run = follow(60.0, 0, fixed);
  EXPECT_EQ(run.delay_ns, 50 * kMs);
  EXPECT_LT(run.worst_lag_error_ns, 2.0);

  FollowerOptions none;
  none.fixed_delay_ns = 0;
  InputFollower follower(none);
  follower.push(at_source_time(0), kArrivalBase_ns, 0);
  follower.push(at_source_time(30 * kMs), kArrivalBase_ns + 30 * kMs, 0);
  FollowedInput in;
  for (int64_t now = kArrivalBase_ns + 30 * kMs; now < kArrivalBase_ns + 60 * kMs; now += kMs) {
    ASSERT_TRUE(follower.at(now, in));
    EXPECT_EQ(in.sample.t_ns, 30 * kMs) << "the newest, held: no interpolation";
  }
  follower.push(at_source_time(60 * kMs), kArrivalBase_ns + 60 * kMs, 0);
  EXPECT_EQ(follower.counts().intervals_late, 1u) << "the hand waited at 30 ms for it";
}

TEST(InputFollower, AGapOverTheMaxGapHoldsTheEarlierSampleUntilTheLaterIsDue) {
  InputFollower follower(FollowerOptions{});  // max gap 0.25 s
  const int64_t arrival0 = kArrivalBase_ns;
  // 100 Hz to 100 ms, then nothing until 400 ms (a 0.3 s gap), then 100 Hz again
  for (int64_t t = 0; t <= 100 * kMs; t += 10 * kMs)
    follower.push(at_source_time(t), arrival0 + t, 0);
  FollowedInput in;
  for (int64_t now = arrival0 + 100 * kMs; now < arrival0 + 400 * kMs; now += kMs) {
    ASSERT_TRUE(follower.at(now, in));
  }
  EXPECT_EQ(in.sample.t_ns, 100 * kMs) << "held at the last sample before the gap";
  for (int64_t t = 400 * kMs; t <= 500 * kMs; t += 10 * kMs) {
    follower.push(at_source_time(t), arrival0 + t, 0);
  }
  const int64_t delay_ns = follower.delay_ns();
  EXPECT_EQ(delay_ns, 12 * kMs);
  // until the shown time reaches 400 ms the hand stays at 100 ms; then it follows
  ASSERT_TRUE(follower.at(arrival0 + 400 * kMs + delay_ns - kMs, in));
  EXPECT_EQ(in.sample.t_ns, 100 * kMs);
  ASSERT_TRUE(follower.at(arrival0 + 405 * kMs + delay_ns, in));
  EXPECT_EQ(in.sample.t_ns, 405 * kMs);
  const auto& c = follower.counts();
  EXPECT_EQ(c.gaps_not_bridged, 1u);
  EXPECT_EQ(c.intervals_late, 0u) << "a gap not bridged is not also late";
  EXPECT_EQ(c.intervals_interpolated, 20u);
  EXPECT_EQ(c.longest_interval_ns, 300 * kMs);
}

TEST(InputFollower, AGapTheDelayDoesNotCoverIsCountedLate) {
  InputFollower follower(FollowerOptions{});
  const int64_t arrival0 = kArrivalBase_ns;
  for (int64_t t = 0; t <= 100 * kMs; t += 10 * kMs)
    follower.push(at_source_time(t), arrival0 + t, 0);
  FollowedInput in;
  for (int64_t now = arrival0 + 100 * kMs; now < arrival0 + 200 * kMs; now += kMs) {
    ASSERT_TRUE(follower.at(now, in));
  }
  follower.push(at_source_time(200 * kMs), arrival0 + 200 * kMs, 0);  // 0.1 s: within the max gap
  EXPECT_EQ(follower.counts().intervals_late, 1u) << "the hand had reached 100 ms and waited";
  EXPECT_EQ(follower.counts().gaps_bridged, 0u);
}

TEST(InputFollower, ANewSourceStartsAfresh) {
  InputFollower follower(FollowerOptions{});
  for (int64_t t = 0; t <= 100 * kMs; t += 10 * kMs) {
    follower.push(at_source_time(t), kArrivalBase_ns + t, 0);
  }
  follower.reset();
  FollowedInput in;
  EXPECT_FALSE(follower.at(kArrivalBase_ns + 101 * kMs, in));
  // a timeline that starts again at 0, with another offset
  follower.push(at_source_time(0), kArrivalBase_ns + 200 * kMs, 0);
  ASSERT_TRUE(follower.at(kArrivalBase_ns + 201 * kMs, in));
  EXPECT_EQ(in.sample.t_ns, 0);
  EXPECT_EQ(follower.counts().intervals, 10u) << "no interval joins the two sources";
}

}  // namespace
}  // namespace vcockpit::physics_io
