// FaultService and ImpairedLink in virtual time: requests carried out on the loop's thread, wire
// faults on a link the event loop serves, faults ending at their deadline, and call() from
// another thread answered by poll().
#include "vdrive/control/fault_service.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <memory>
#include <sstream>
#include <thread>

#include "vdrive/fault/impaired_link.hpp"
#include "vdrive/fault/wire_impairment.hpp"
#include "vdrive/link/loopback_link.hpp"
#include "vdrive/network/network.hpp"
#include "vdrive/runtime/event_loop.hpp"
#include "tests/support/runtime_test_support.hpp"

namespace vdrive::control {
namespace {

using ::testing::HasSubstr;
using Op = ControlRequest::Op;

class FaultServiceTest : public ::testing::Test {
protected:
  ControlRequest inject(fault::FaultKind kind, Nanos duration = 0) {
    ControlRequest r;
    r.op = Op::inject;
    r.fault.kind = kind;
    r.fault.duration = duration;
    return r;
  }
  // One BRD of the AL status through the loop; the reply's working counter, or -1 if no reply.
  int round_trip() {
    const std::vector<std::uint8_t> frame = test::ethercat_frame(0x07, 0, 0x0130, 2);
    EXPECT_TRUE(master_->send(frame));
    runtime::run_pending(net_, impaired_, clock_, counters_);
    std::vector<std::uint8_t> buf(link::kMaxFrame);
    const std::size_t n = master_->receive(buf, 0);
    if (n == 0) return -1;
    buf.resize(n);
    return test::first_wkc(buf);
  }

  VirtualClock clock_{1'000'000'000};
  network::Network net_{std::vector<std::string>{"a6b", "ds5c1"}, clock_};
  std::pair<std::unique_ptr<link::LoopbackLink>, std::unique_ptr<link::LoopbackLink>> ends_ = link::make_loopback_pair();
  link::LoopbackLink* master_ = ends_.first.get();
  fault::WireImpairment wire_{7};
  fault::ImpairedLink impaired_{*ends_.second, wire_, net_, clock_};
  FaultService service_{net_, &wire_, &impaired_};
  runtime::LoopCounters counters_;
};

TEST_F(FaultServiceTest, CleanWireIsNotEngagedAndPassesFrames) {
  EXPECT_FALSE(impaired_.engaged());
  EXPECT_EQ(round_trip(), 2);
}

TEST_F(FaultServiceTest, ArmedFaultsAreInjectedWhenTheirTimeComes) {
  fault::FaultSpec jam;
  jam.kind = fault::FaultKind::jam;
  jam.slave = 2;
  fault::FaultSpec bad = jam;
  bad.slave = 9;  // refused when its time comes: logged, the others still go in
  const Nanos t0 = clock_.now();
  service_.arm(jam, t0 + 5'000'000, "bench.yaml:9");
  service_.arm(bad, t0 + 1'000'000, "bench.yaml:10");
  EXPECT_TRUE(service_.has_armed());
  EXPECT_EQ(service_.next_deadline(), t0 + 1'000'000);
  service_.poll(t0 + 4'000'000);
  EXPECT_TRUE(service_.injector().active().empty());
  EXPECT_EQ(service_.next_deadline(), t0 + 5'000'000);
  service_.poll(t0 + 5'000'000);
  ASSERT_EQ(service_.injector().active().size(), 1u);
  EXPECT_EQ(service_.injector().active()[0].spec.kind, fault::FaultKind::jam);
  EXPECT_EQ(service_.injector().active()[0].spec.slave, 2);
  EXPECT_GT(service_.next_deadline(), t0 + 5'000'000) << "nothing armed is left";
}

TEST_F(FaultServiceTest, DropCutsTheLineUntilCleared) {
  const ControlReply r = service_.handle(inject(fault::FaultKind::drop), clock_.now());
  ASSERT_TRUE(r.ok()) << r.error;
  EXPECT_EQ(r.id, 1);
  EXPECT_TRUE(impaired_.engaged());
  EXPECT_EQ(round_trip(), -1);

  ControlRequest list;
  const ControlReply l = service_.handle(list, clock_.now());
  ASSERT_EQ(l.faults.size(), 1u);
  EXPECT_EQ(l.faults[0].id, 1);
  EXPECT_EQ(l.faults[0].kind, "drop");
  EXPECT_EQ(l.faults[0].remaining, -1);

  ControlRequest clear;
  clear.op = Op::clear;
  clear.id = 1;
  EXPECT_TRUE(service_.handle(clear, clock_.now()).ok());
  EXPECT_FALSE(impaired_.engaged());
  EXPECT_EQ(round_trip(), 2);
  const ControlReply again = service_.handle(clear, clock_.now());
  EXPECT_EQ(again.status, ControlReply::Status::bad_request);
  EXPECT_EQ(again.error, "no active fault 1");
}

TEST_F(FaultServiceTest, FaultEndsAtItsDeadlineThroughPoll) {
  ASSERT_TRUE(service_.handle(inject(fault::FaultKind::drop, 100'000'000), clock_.now()).ok());
  EXPECT_EQ(service_.next_deadline(), clock_.now() + 100'000'000);
  clock_.advance(99'000'000);
  service_.poll(clock_.now());
  EXPECT_EQ(round_trip(), -1);
  clock_.advance(1'000'000);
  service_.poll(clock_.now());
  EXPECT_TRUE(service_.injector().active().empty());
  EXPECT_FALSE(impaired_.engaged());
  EXPECT_EQ(round_trip(), 2);
}

// What `vdrive run` shows at info level: captures the default logger's lines while it lives.
class CapturedLog {
public:
  CapturedLog() : sink_(std::make_shared<spdlog::sinks::ostream_sink_mt>(text_)) {
    sink_->set_pattern("%v");
    spdlog::default_logger()->sinks().push_back(sink_);
    level_ = spdlog::default_logger()->level();
    spdlog::default_logger()->set_level(spdlog::level::info);
  }
  ~CapturedLog() {
    auto& sinks = spdlog::default_logger()->sinks();
    sinks.erase(std::remove(sinks.begin(), sinks.end(), sink_), sinks.end());
    spdlog::default_logger()->set_level(level_);
  }
  std::string text() const { return text_.str(); }

private:
  std::ostringstream text_;
  std::shared_ptr<spdlog::sinks::ostream_sink_mt> sink_;
  spdlog::level::level_enum level_;
};

TEST_F(FaultServiceTest, AFaultEndingByItsDurationIsLogged) {
  const CapturedLog log;
  ASSERT_TRUE(service_.handle(inject(fault::FaultKind::drop, 100'000'000), clock_.now()).ok());
  ASSERT_TRUE(service_.handle(inject(fault::FaultKind::duplicate), clock_.now()).ok());
  EXPECT_THAT(log.text(), HasSubstr("fault 1 injected: drop"));
  clock_.advance(99'000'000);
  service_.poll(clock_.now());
  EXPECT_THAT(log.text(), ::testing::Not(HasSubstr("ended")));
  clock_.advance(1'000'000);
  service_.poll(clock_.now());
  EXPECT_THAT(log.text(), HasSubstr("fault 1 ended: its duration ran out (drop both ways p=1 for 100000 us)\n"));
  EXPECT_THAT(log.text(), ::testing::Not(HasSubstr("fault 2 ended"))) << "the other one lasts until cleared";
  clock_.advance(1'000'000'000);
  service_.poll(clock_.now());
  EXPECT_EQ(service_.injector().active().size(), 1u);
  const std::string once = log.text();
  EXPECT_EQ(once.find("fault 1 ended"), once.rfind("fault 1 ended")) << "logged once";
}

TEST_F(FaultServiceTest, DelayedRepliesLeaveAtTheirTime) {
  ControlRequest r = inject(fault::FaultKind::delay);
  r.fault.delay = 5'000'000;
  r.fault.direction = fault::WireDirection::to_master;
  ASSERT_TRUE(service_.handle(r, clock_.now()).ok());
  EXPECT_EQ(round_trip(), -1);  // executed, but held on the way back
  clock_.advance(5'000'000);
  runtime::run_pending(net_, impaired_, clock_, counters_);
  std::vector<std::uint8_t> buf(link::kMaxFrame);
  EXPECT_GT(master_->receive(buf, 0), 0u);
}

TEST_F(FaultServiceTest, CorruptedFramesAreCountedByTheLineNotAnswered) {
  ControlRequest r = inject(fault::FaultKind::corrupt);
  r.fault.direction = fault::WireDirection::to_slaves;
  ASSERT_TRUE(service_.handle(r, clock_.now()).ok());
  EXPECT_EQ(round_trip(), -1);
  EXPECT_EQ(wire_.counters(fault::Direction::to_slaves).corrupted, 1u);
}

TEST_F(FaultServiceTest, RefusalsFromTheInjectorAreBadRequests) {
  ControlRequest r = inject(fault::FaultKind::overload);
  r.fault.slave = 9;
  const ControlReply reply = service_.handle(r, clock_.now());
  EXPECT_EQ(reply.status, ControlReply::Status::bad_request);
  EXPECT_FALSE(reply.error.empty());
}

TEST_F(FaultServiceTest, ClearAllCountsAndCleans) {
  ASSERT_TRUE(service_.handle(inject(fault::FaultKind::drop), clock_.now()).ok());
  ASSERT_TRUE(service_.handle(inject(fault::FaultKind::duplicate), clock_.now()).ok());
  ControlRequest all;
  all.op = Op::clear_all;
  EXPECT_EQ(service_.handle(all, clock_.now()).cleared, 2);
  EXPECT_FALSE(impaired_.engaged());
}

TEST_F(FaultServiceTest, CallFromAnotherThreadIsAnsweredByPoll) {
  ControlReply reply;
  std::thread caller([&] { reply = service_.call(inject(fault::FaultKind::drop), 5'000'000'000); });
  // The loop's side: poll until the caller has its answer.
  while (service_.injector().active().empty()) service_.poll(clock_.now());
  caller.join();
  ASSERT_TRUE(reply.ok()) << reply.error;
  EXPECT_EQ(reply.id, 1);
}

TEST_F(FaultServiceTest, CallTimesOutWhenTheLoopDoesNotPoll) {
  const ControlReply reply = service_.call(ControlRequest{}, 20'000'000);
  EXPECT_EQ(reply.status, ControlReply::Status::failed);
  EXPECT_THAT(reply.error, HasSubstr("did not answer"));
  // The late reply to that request is not mistaken for the next one's.
  service_.poll(clock_.now());
  ControlReply next;
  std::thread caller([&] { next = service_.call(inject(fault::FaultKind::drop), 5'000'000'000); });
  while (service_.injector().active().empty()) service_.poll(clock_.now());
  caller.join();
  EXPECT_EQ(next.id, 1);
}

}  // namespace
}  // namespace vdrive::control
