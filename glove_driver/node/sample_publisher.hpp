#pragma once
// The glove driver's DDS side: validates each sample, publishes it on cockpit/hand_sample, and
// reports counts on cockpit/node_status about once a second: hand::InputCounts, the same counts
// the physics node keeps (what loading the log counted, the validator's, and the intervals
// between the samples it publishes, classified against --max-gap as the physics node does).
//
// Both modes wait for their readers (--wait-readers) to match before the first sample, so a
// reader started first (the physics node, a recorder) gets the run from its start.
// Stream mode: at the source's pace (hand_stream profile). Lockstep: reliable keep-all (reliable
// profile), and waits for the readers' acknowledgement after the last sample, so a replay is
// lossless however fast it runs.

#include <cstdint>
#include <string>

#include "dds/dds_participant.hpp"
#include "hand/sample_intervals.hpp"
#include "hand/sample_validator.hpp"

namespace vcockpit::glove {

struct PublisherOptions {
  uint32_t hand_id = 0;
  bool lockstep = false;
  int readers = 1;               // readers to wait for before the first sample (0: none)
  double match_timeout_s = 30.0;  // lockstep fails after it; a stream starts anyway
  std::string node_name = "glove_driver";
  int64_t max_gap_ns = hand::kDefaultMaxGap_ns;
};

class SamplePublisher {
 public:
  SamplePublisher(DdsParticipant& participant, const hand::HandModel& hand,
                  const PublisherOptions& options);

  // Blocks until `readers` readers matched. False on shutdown, or on timeout in lockstep; a
  // stream starts anyway after the timeout (what it sends before a reader matches is that
  // reader's to count as missed at the start).
  bool wait_for_readers();
  // Validates and writes; false if the sample was rejected or the middleware refused it.
  bool publish(hand::GloveSample sample);
  // Publishes node_status when a second has passed since the last one.
  void tick(int64_t now_ns);
  // Lockstep: waits until every subscriber acknowledged everything. Publishes a final status.
  bool finish();

  // What was counted before the samples reached the validator (reading a log: clamped values,
  // missing columns).
  void add_load_counts(const hand::InputCounts& counts) { load_counts_ += counts; }

  // Everything counted: loading, validation, intervals.
  hand::InputCounts counts() const;
  uint64_t published() const { return published_; }
  int matched_readers() const { return writer_.matched_count(); }
  uint64_t write_failures() const { return write_failures_; }

 private:
  void publish_status(cockpit::NodeState state, int64_t now_ns);

  PublisherOptions options_;
  hand::SampleValidator validator_;
  Writer<cockpit::HandSample> writer_;
  Writer<cockpit::NodeStatus> status_writer_;
  cockpit::HandSample message_;
  uint64_t published_ = 0;
  uint64_t write_failures_ = 0;
  hand::InputCounts load_counts_;
  hand::InputCounts interval_counts_;
  hand::IntervalTracker intervals_;
  int64_t last_t_ns_ = 0;
  int64_t last_status_ns_ = 0;
  uint64_t published_at_last_status_ = 0;
};

}  // namespace vcockpit::glove
