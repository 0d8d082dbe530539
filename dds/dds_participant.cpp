#include "dds/dds_participant.hpp"

#include <fastdds/dds/core/status/LivelinessChangedStatus.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/rtps/transport/test_UDPv4TransportDescriptor.h>

#include <algorithm>
#include <cstdlib>
#include <memory>
#include <fstream>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>

#include "common/clock.hpp"

namespace vcockpit {
namespace {

void load_profiles_once(const std::string& file) {
  static std::mutex mutex;
  static std::set<std::string> loaded;
  std::lock_guard<std::mutex> lock(mutex);
  if (loaded.count(file)) return;
  auto* factory = dds::DomainParticipantFactory::get_instance();
  if (factory->load_XML_profiles_file(file) != ReturnCode_t::RETCODE_OK) {
    throw std::runtime_error(file + ": Fast DDS could not load the QoS profiles (see its log)");
  }
  loaded.insert(file);
}

// Polls a condition until it holds or the timeout passes (start-up and shutdown paths only).
template <class Condition>
bool poll_until(Condition condition, int64_t timeout_ns) {
  const int64_t deadline = monotonic_now_ns() + timeout_ns;
  while (!condition()) {
    if (monotonic_now_ns() >= deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return true;
}

}  // namespace

DdsDuration to_dds_duration(int64_t ns) {
  return DdsDuration(static_cast<int32_t>(ns / 1'000'000'000),
                         static_cast<uint32_t>(ns % 1'000'000'000));
}

int UntypedWriter::matched_count() const {
  dds::PublicationMatchedStatus status;
  writer_->get_publication_matched_status(status);
  return status.current_count;
}

bool UntypedWriter::wait_for_matched(int count, int64_t timeout_ns) const {
  return poll_until([&] { return matched_count() >= count; }, timeout_ns);
}

bool UntypedWriter::wait_for_acknowledgments(int64_t timeout_ns) const {
  return writer_->wait_for_acknowledgments(to_dds_duration(timeout_ns)) ==
         ReturnCode_t::RETCODE_OK;
}

void wait_for_acknowledgments(std::initializer_list<const UntypedWriter*> writers, int64_t timeout_ns) {
  const int64_t deadline_ns = monotonic_now_ns() + timeout_ns;
  for (const UntypedWriter* writer : writers) {
    const int64_t left_ns = deadline_ns - monotonic_now_ns();
    if (left_ns <= 0) break;
    writer->wait_for_acknowledgments(left_ns);
  }
}

int UntypedReader::matched_count() const {
  dds::SubscriptionMatchedStatus status;
  reader_->get_subscription_matched_status(status);
  return status.current_count;
}

bool UntypedReader::wait_for_matched(int count, int64_t timeout_ns) const {
  return poll_until([&] { return matched_count() >= count; }, timeout_ns);
}

int UntypedReader::alive_writer_count() const {
  dds::LivelinessChangedStatus status;
  reader_->get_liveliness_changed_status(status);
  return status.alive_count;
}

bool UntypedReader::wait_for_data(int64_t timeout_ns) const {
  return reader_->wait_for_unread_message(to_dds_duration(timeout_ns));
}

namespace {

// A secured profile (it names the authentication plugin, as config/qos.xml's "secure" does) gets
// the identity's files from the PKI directory (scripts/make-pki): Fast DDS reads no environment in
// its XML, and the files belong to the machine, not to the project's configuration.
void add_security_files(const DdsOptions& options, dds::DomainParticipantQos& qos) {
  auto& properties = qos.properties().properties();
  const bool secured = std::any_of(properties.begin(), properties.end(), [](const auto& p) {
    return p.name() == "dds.sec.auth.plugin";
  });
  if (!secured) {
    if (!options.pki_dir.empty()) {
      throw std::invalid_argument("participant profile '" + options.participant_profile +
                                  "' is not secured, and a PKI directory was given (" +
                                  options.pki_dir + "): use --participant secure");
    }
    return;
  }
  if (options.pki_dir.empty()) {
    throw std::invalid_argument("participant profile '" + options.participant_profile +
                                "' is secured: give --pki DIR (or VCOCKPIT_PKI_DIR), made by "
                                "scripts/make-pki DIR");
  }
  if (options.identity.empty()) {
    throw std::invalid_argument("participant profile '" + options.participant_profile +
                                "' is secured: give --identity NAME (or VCOCKPIT_IDENTITY)");
  }
  const std::string& id = options.identity;
  const std::pair<const char*, std::string> files[] = {
      {"dds.sec.auth.builtin.PKI-DH.identity_ca", "identity_ca.pem"},
      {"dds.sec.auth.builtin.PKI-DH.identity_certificate", id + "_cert.pem"},
      {"dds.sec.auth.builtin.PKI-DH.private_key", id + "_key.pem"},
      {"dds.sec.access.builtin.Access-Permissions.permissions_ca", "permissions_ca.pem"},
      {"dds.sec.access.builtin.Access-Permissions.governance", "governance.p7s"},
      {"dds.sec.access.builtin.Access-Permissions.permissions", "permissions_" + id + ".p7s"},
  };
  for (const auto& [name, file] : files) {
    const std::string path = options.pki_dir + "/" + file;
    if (!std::ifstream(path)) {
      throw std::invalid_argument("secured participant: cannot read " + path + " (identity '" +
                                  id + "'; scripts/make-pki makes them)");
    }
    properties.emplace_back(name, "file://" + path);
  }
}

// A lossy profile (config/qos.xml's "lossy": its property vcockpit.drop_percent, overridden by
// VCOCKPIT_DROP_PERCENT) sends through Fast DDS's test UDP transport, which drops that share of
// the datagrams it sends: packet loss without the kernel's netem. The transport has no interface
// whitelist, so the participant listens and announces on 127.0.0.1 only (no multicast locator).
void add_lossy_transport(const DdsOptions& options, dds::DomainParticipantQos& qos) {
  const auto& properties = qos.properties().properties();
  const auto it = std::find_if(properties.begin(), properties.end(),
                               [](const auto& p) { return p.name() == "vcockpit.drop_percent"; });
  if (it == properties.end()) return;
  std::string text = it->value();
  std::string where = options.qos_file + ": profile '" + options.participant_profile +
                      "', property vcockpit.drop_percent";
  if (const char* env = std::getenv("VCOCKPIT_DROP_PERCENT"); env && *env) {
    text = env;
    where = "VCOCKPIT_DROP_PERCENT";
  }
  int percent = -1;
  try {
    std::size_t used = 0;
    percent = std::stoi(text, &used);
    if (used != text.size()) percent = -1;
  } catch (const std::exception&) {
  }
  if (percent < 0 || percent > 100) {
    throw std::invalid_argument(where + ": '" + text + "' is not a whole percentage 0..100");
  }
  auto lossy = std::make_shared<eprosima::fastdds::rtps::test_UDPv4TransportDescriptor>();
  lossy->percentageOfMessagesToDrop = static_cast<uint8_t>(percent);
  auto& transport = qos.transport();
  transport.use_builtin_transports = false;
  transport.user_transports.clear();
  transport.user_transports.push_back(lossy);
  eprosima::fastrtps::rtps::Locator_t loopback;
  eprosima::fastrtps::rtps::IPLocator::setIPv4(loopback, 127, 0, 0, 1);
  auto& rtps = qos.wire_protocol();
  rtps.builtin.metatrafficUnicastLocatorList.clear();
  rtps.builtin.metatrafficUnicastLocatorList.push_back(loopback);
  rtps.builtin.metatrafficMulticastLocatorList.clear();
  rtps.default_unicast_locator_list.clear();
  rtps.default_unicast_locator_list.push_back(loopback);
  rtps.default_multicast_locator_list.clear();
}

}  // namespace

DdsParticipant::DdsParticipant(const DdsOptions& options, const std::string& node_name)
    : domain_id_(options.domain_id) {
  load_profiles_once(options.qos_file);
  auto* factory = dds::DomainParticipantFactory::get_instance();
  dds::DomainParticipantQos qos;
  if (factory->get_participant_qos_from_profile(options.participant_profile, qos) !=
      ReturnCode_t::RETCODE_OK) {
    throw std::runtime_error(options.qos_file + ": no participant profile '" +
                             options.participant_profile + "'");
  }
  qos.name(node_name);
  add_security_files(options, qos);
  add_lossy_transport(options, qos);
  participant_ = factory->create_participant(options.domain_id, qos);
  if (!participant_) {
    throw std::runtime_error("cannot create a DDS participant on domain " +
                             std::to_string(options.domain_id) + " with profile '" +
                             options.participant_profile + "'" +
                             (options.pki_dir.empty() ? std::string()
                                                      : " (identity '" + options.identity +
                                                            "' in " + options.pki_dir +
                                                            ": is it signed by this PKI's CAs?)"));
  }
  publisher_ = participant_->create_publisher(dds::PUBLISHER_QOS_DEFAULT);
  subscriber_ = participant_->create_subscriber(dds::SUBSCRIBER_QOS_DEFAULT);
  if (!publisher_ || !subscriber_) throw std::runtime_error("cannot create publisher/subscriber");
}

DdsParticipant::~DdsParticipant() {
  if (!participant_) return;
  participant_->delete_contained_entities();
  dds::DomainParticipantFactory::get_instance()->delete_participant(participant_);
}

dds::Topic* DdsParticipant::find_or_create_topic(const std::string& name,
                                                 dds::TypeSupport type) {
  if (auto it = topics_.find(name); it != topics_.end()) return it->second;
  if (type.register_type(participant_) != ReturnCode_t::RETCODE_OK) {
    throw std::runtime_error("cannot register type " + type.get_type_name());
  }
  dds::Topic* topic = participant_->create_topic(name, type.get_type_name(), dds::TOPIC_QOS_DEFAULT);
  if (!topic) throw std::runtime_error("cannot create topic " + name);
  topics_[name] = topic;
  return topic;
}

dds::DataWriter* DdsParticipant::create_writer(dds::Topic* topic, const std::string& profile) {
  dds::DataWriter* writer = publisher_->create_datawriter_with_profile(topic, profile);
  if (!writer) {
    throw std::runtime_error("cannot create a writer on " + topic->get_name() +
                             " with QoS profile '" + profile + "'");
  }
  return writer;
}

dds::DataReader* DdsParticipant::create_reader(dds::Topic* topic, const std::string& profile) {
  dds::DataReader* reader = subscriber_->create_datareader_with_profile(topic, profile);
  if (!reader) {
    throw std::runtime_error("cannot create a reader on " + topic->get_name() +
                             " with QoS profile '" + profile + "'");
  }
  return reader;
}

}  // namespace vcockpit
