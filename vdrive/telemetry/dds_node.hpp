#pragma once
// DdsNode: one Fast DDS participant in a domain with the telemetry's types and topics
// registered, and writers/readers with each topic's QoS (docs/telemetry.md "QoS"). Used by the
// publisher inside vdrive and by the `vdrive telemetry` client; only their .cpp files see it.
#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>

#include <array>

#include "vdrive/telemetry/topics.hpp"

namespace vdrive::telemetry {

class DdsNode {
public:
  explicit DdsNode(int domain);  // throws DdsError
  ~DdsNode();
  DdsNode(const DdsNode&) = delete;
  DdsNode& operator=(const DdsNode&) = delete;

  eprosima::fastdds::dds::DataWriter* writer(Topic t);
  eprosima::fastdds::dds::DataReader* reader(Topic t);

private:
  eprosima::fastdds::dds::DomainParticipant* participant_ = nullptr;
  eprosima::fastdds::dds::Publisher* publisher_ = nullptr;
  eprosima::fastdds::dds::Subscriber* subscriber_ = nullptr;
  std::array<eprosima::fastdds::dds::Topic*, 5> topics_{};
};

}  // namespace vdrive::telemetry
