// The telemetry's Fast DDS participant, topics and QoS. See dds_node.hpp.
#include "vdrive/telemetry/dds_node.hpp"

#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>
#include <fmt/core.h>

#include <cstdlib>
#include <string>

#include "TelemetryPubSubTypes.h"

namespace vdrive::telemetry {
namespace dds = eprosima::fastdds::dds;
namespace {

dds::TypeSupport type_of(Topic t) {
  switch (t) {
    case Topic::axis_state: return dds::TypeSupport(new vdrive::msg::dds_::AxisState_PubSubType());
    case Topic::bus_state: return dds::TypeSupport(new vdrive::msg::dds_::BusState_PubSubType());
    case Topic::events: return dds::TypeSupport(new vdrive::msg::dds_::Event_PubSubType());
    case Topic::control_request: return dds::TypeSupport(new vdrive::msg::dds_::ControlRequest_PubSubType());
    case Topic::control_reply: return dds::TypeSupport(new vdrive::msg::dds_::ControlReply_PubSubType());
  }
  throw DdsError("unknown topic");
}

// Every topic is reliable (a subscriber that keeps up sees every sample, which the rate test
// counts; ROS 2's default subscription is reliable too). Samples are volatile (only the present
// matters). Events are transient-local so a late subscriber gets the recent ones. So are control
// requests and replies: discovery is not symmetric, so a request or reply written before the
// other end has matched the writer would otherwise be lost; a client's requests die with it.
struct TopicQos {
  bool transient_local = false;
  int depth = 0;
};

TopicQos qos_of(Topic t) {
  switch (t) {
    case Topic::axis_state:
    case Topic::bus_state: return {false, 100};
    case Topic::events: return {true, 100};
    case Topic::control_request:
    case Topic::control_reply: return {true, 10};
  }
  return {};
}

}  // namespace

int resolve_domain(std::optional<int> option) {
  if (option) {
    if (*option < 0 || *option > kMaxDomain) throw DomainError(fmt::format("--domain {}: not in 0..{}", *option, kMaxDomain));
    return *option;
  }
  const char* env = std::getenv("ROS_DOMAIN_ID");
  if (env == nullptr || *env == '\0') return 0;
  char* end = nullptr;
  const long v = std::strtol(env, &end, 10);
  if (*end != '\0' || v < 0 || v > kMaxDomain) throw DomainError(fmt::format("ROS_DOMAIN_ID '{}': not an integer in 0..{}", env, kMaxDomain));
  return static_cast<int>(v);
}

DdsNode::DdsNode(int domain) {
  dds::DomainParticipantQos pq = dds::PARTICIPANT_QOS_DEFAULT;
  pq.name("vdrive");
  participant_ = dds::DomainParticipantFactory::get_instance()->create_participant(static_cast<dds::DomainId_t>(domain), pq);
  if (participant_ == nullptr) throw DdsError(fmt::format("cannot create a DDS participant in domain {}", domain));
  publisher_ = participant_->create_publisher(dds::PUBLISHER_QOS_DEFAULT);
  subscriber_ = participant_->create_subscriber(dds::SUBSCRIBER_QOS_DEFAULT);
  for (const Topic t : {Topic::axis_state, Topic::bus_state, Topic::events, Topic::control_request, Topic::control_reply}) {
    dds::TypeSupport type = type_of(t);
    type.register_type(participant_);
    topics_[static_cast<std::size_t>(t)] = participant_->create_topic(topic_name(t), type.get_type_name(), dds::TOPIC_QOS_DEFAULT);
  }
  for (dds::Topic* topic : topics_)
    if (topic == nullptr || publisher_ == nullptr || subscriber_ == nullptr) throw DdsError("cannot create the telemetry topics");
}

DdsNode::~DdsNode() {
  participant_->delete_contained_entities();
  dds::DomainParticipantFactory::get_instance()->delete_participant(participant_);
}

dds::DataWriter* DdsNode::writer(Topic t) {
  const TopicQos q = qos_of(t);
  dds::DataWriterQos wq = dds::DATAWRITER_QOS_DEFAULT;
  wq.reliability().kind = dds::RELIABLE_RELIABILITY_QOS;
  wq.durability().kind = q.transient_local ? dds::TRANSIENT_LOCAL_DURABILITY_QOS : dds::VOLATILE_DURABILITY_QOS;
  wq.history().kind = dds::KEEP_LAST_HISTORY_QOS;
  wq.history().depth = q.depth;
  dds::DataWriter* w = publisher_->create_datawriter(topics_[static_cast<std::size_t>(t)], wq);
  if (w == nullptr) throw DdsError(fmt::format("cannot create a writer on {}", topic_name(t)));
  return w;
}

dds::DataReader* DdsNode::reader(Topic t) {
  const TopicQos q = qos_of(t);
  dds::DataReaderQos rq = dds::DATAREADER_QOS_DEFAULT;
  rq.reliability().kind = dds::RELIABLE_RELIABILITY_QOS;
  rq.durability().kind = q.transient_local ? dds::TRANSIENT_LOCAL_DURABILITY_QOS : dds::VOLATILE_DURABILITY_QOS;
  rq.history().kind = dds::KEEP_LAST_HISTORY_QOS;
  rq.history().depth = q.depth;
  dds::DataReader* r = subscriber_->create_datareader(topics_[static_cast<std::size_t>(t)], rq);
  if (r == nullptr) throw DdsError(fmt::format("cannot create a reader on {}", topic_name(t)));
  return r;
}

}  // namespace vdrive::telemetry
