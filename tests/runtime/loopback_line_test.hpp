#pragma once
// A test fixture: a Network of real products in virtual time, served through one end of a
// loopback pair (line_); the test is the master at the other end (master_).
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "common/clock.hpp"
#include "vdrive/link/loopback_link.hpp"
#include "vdrive/network/network.hpp"
#include "vdrive/runtime/loop_counters.hpp"

namespace vdrive::test {

class LoopbackLineTest : public ::testing::Test {
protected:
  LoopbackLineTest(const std::vector<std::string>& products, Nanos start) : clock_(start), net_(products, clock_) {}

  VirtualClock clock_;
  network::Network net_;
  std::pair<std::unique_ptr<link::LoopbackLink>, std::unique_ptr<link::LoopbackLink>> ends_ =
      link::make_loopback_pair();
  link::Link& master_ = *ends_.first;
  link::Link& line_ = *ends_.second;
  runtime::LoopCounters counters_;
};

}  // namespace vdrive::test
