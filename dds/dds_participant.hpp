#pragma once
// A DDS participant with the project's conventions: QoS profiles from the XML file, one topic per
// IDL type (TopicTraits), writers and readers created by profile name (stream, state, event,
// reliable). Start-up errors throw std::runtime_error; the Writer/Reader calls used in loops
// never throw or allocate.
//
// Writers and readers are owned by the participant: they must not outlive it.

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/topic/Topic.hpp>

#include <cstdint>
#include <map>
#include <initializer_list>
#include <string>

#include "dds/dds_options.hpp"
#include "idl/topics/topic_traits.hpp"

namespace vcockpit {

namespace dds = eprosima::fastdds::dds;
using DdsDuration = eprosima::fastrtps::Duration_t;

DdsDuration to_dds_duration(int64_t ns);

class UntypedWriter {
 public:
  explicit UntypedWriter(dds::DataWriter* writer = nullptr) : writer_(writer) {}
  int matched_count() const;
  // Waits until at least `count` readers matched; false on timeout.
  bool wait_for_matched(int count, int64_t timeout_ns) const;
  // Waits until every matched reader acknowledged everything written (reliable only).
  bool wait_for_acknowledgments(int64_t timeout_ns) const;
  dds::DataWriter* raw() const { return writer_; }

 protected:
  dds::DataWriter* writer_;
};

// Until every matched reader of each writer acknowledged everything written, on one budget for
// all (a stop stays quick however many readers lag).
void wait_for_acknowledgments(std::initializer_list<const UntypedWriter*> writers, int64_t timeout_ns);

template <class T>
class Writer : public UntypedWriter {
 public:
  using UntypedWriter::UntypedWriter;
  // False if the middleware refused (e.g. a reliable history stayed full past max_blocking_time).
  bool write(const T& sample) { return writer_->write(const_cast<T*>(&sample)); }
};

class UntypedReader {
 public:
  explicit UntypedReader(dds::DataReader* reader = nullptr) : reader_(reader) {}
  int matched_count() const;
  bool wait_for_matched(int count, int64_t timeout_ns) const;
  // Writers whose liveliness is currently asserted (a killed writer drops out after its lease).
  int alive_writer_count() const;
  // Waits until unread data is available; false on timeout.
  bool wait_for_data(int64_t timeout_ns) const;
  dds::DataReader* raw() const { return reader_; }

 protected:
  dds::DataReader* reader_;
};

template <class T>
class Reader : public UntypedReader {
 public:
  using UntypedReader::UntypedReader;
  // Takes the next valid sample; false when none is left.
  bool take(T& out, dds::SampleInfo* info_out = nullptr) {
    dds::SampleInfo info;
    while (reader_->take_next_sample(&out, &info) == ReturnCode_t::RETCODE_OK) {
      if (!info.valid_data) continue;  // disposals and unregistrations carry no sample
      if (info_out) *info_out = info;
      return true;
    }
    return false;
  }
};

class DdsParticipant {
 public:
  // Loads the QoS file (once per process) and joins the domain with the options' profile.
  DdsParticipant(const DdsOptions& options, const std::string& node_name);
  ~DdsParticipant();
  DdsParticipant(const DdsParticipant&) = delete;
  DdsParticipant& operator=(const DdsParticipant&) = delete;

  template <class T>
  Writer<T> make_writer(const std::string& profile) {
    return Writer<T>(create_writer(topic<T>(), profile));
  }
  template <class T>
  Reader<T> make_reader(const std::string& profile) {
    return Reader<T>(create_reader(topic<T>(), profile));
  }

  int domain_id() const { return domain_id_; }
  dds::DomainParticipant* raw() const { return participant_; }

 private:
  template <class T>
  dds::Topic* topic() {
    using Traits = TopicTraits<T>;
    return find_or_create_topic(Traits::kName, dds::TypeSupport(new typename Traits::PubSubType()));
  }
  dds::Topic* find_or_create_topic(const std::string& name, dds::TypeSupport type);
  dds::DataWriter* create_writer(dds::Topic* topic, const std::string& profile);
  dds::DataReader* create_reader(dds::Topic* topic, const std::string& profile);

  int domain_id_;
  dds::DomainParticipant* participant_ = nullptr;
  dds::Publisher* publisher_ = nullptr;
  dds::Subscriber* subscriber_ = nullptr;
  std::map<std::string, dds::Topic*> topics_;
};

}  // namespace vcockpit
