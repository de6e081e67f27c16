// The mailbox over SM0/SM1 as a master sees it: header checks and mailbox error replies
// (ETG.1000.6 codes), the counter, the repeat request, the reply queue while SM1 is full, and
// emergencies buffered in Init (A6B L4565-L4569).
#include <gtest/gtest.h>

#include "tests/firmware/coe_test_client.hpp"
#include "tests/firmware/mailbox_test_bench.hpp"
#include "tests/support/allocation_counter.hpp"


namespace vdrive::firmware::mailbox_test {
namespace {

profile::ProductProfile load(const std::string& id) { return profile::load_profile(id); }

// 1018:01 upload request (answered by every product with its vendor id).
std::vector<std::uint8_t> vendor_id_request() { return sdo_payload(0x40, 0x1018, 0x01); }

void expect_mailbox_error(const std::optional<std::vector<std::uint8_t>>& r, std::uint16_t code) {
  ASSERT_TRUE(r.has_value()) << "no reply";
  EXPECT_EQ(r->at(5) & 0x0F, 0) << "type 0: mailbox error";
  EXPECT_EQ(u16_at(*r, 0), 4);
  EXPECT_EQ(u16_at(*r, 6), 0x0001) << "service: error";
  EXPECT_EQ(u16_at(*r, 8), code);
}

class MailboxOnProduct : public ::testing::TestWithParam<std::string> {};

TEST_P(MailboxOnProduct, FoeEoeSoeVoeAreUnsupportedProtocols) {
  Bench b(load(GetParam()));
  b.to_preop();
  for (std::uint8_t type : {0x1, 0x2, 0x4, 0x5, 0xF}) {
    if (type == 0x4 && b.product.foe_details != 0) continue;  // FoE served: tests/firmware/foe/foe_download_test.cpp
    expect_mailbox_error(b.exchange(type, {0, 0, 0, 0, 0, 0, 0, 0, 0, 0}), 0x0002);
  }
}

TEST_P(MailboxOnProduct, TypeZeroOrEmptyIsAnInvalidHeader) {
  Bench b(load(GetParam()));
  b.to_preop();
  expect_mailbox_error(b.exchange(0x0, {1, 2, 3, 4}), 0x0005);
  b.counter = 4;
  ASSERT_EQ(b.send(message(kCoE, 5, {})), 1);
  expect_mailbox_error(b.receive(), 0x0005);
}

TEST_P(MailboxOnProduct, LengthBeyondSm0IsAnInvalidSize) {
  Bench b(load(GetParam()));
  b.to_preop();
  std::vector<std::uint8_t> m = message(kCoE, 1, vendor_id_request());
  const std::uint16_t too_long = static_cast<std::uint16_t>(b.sm0_length() - 6 + 1);
  m[0] = static_cast<std::uint8_t>(too_long);
  m[1] = static_cast<std::uint8_t>(too_long >> 8);
  ASSERT_EQ(b.send(m), 1);
  expect_mailbox_error(b.receive(), 0x0008);
}

TEST_P(MailboxOnProduct, UnknownCoeServiceIsNotSupported) {
  Bench b(load(GetParam()));
  b.to_preop();
  expect_mailbox_error(b.exchange(kCoE, {0x00, 0x90, 0, 0, 0, 0, 0, 0, 0, 0}), 0x0004);  // service 9
  expect_mailbox_error(b.exchange(kCoE, {0x00}), 0x0006);  // shorter than the CoE header
}

TEST_P(MailboxOnProduct, NoMailboxInInit) {
  Bench b(load(GetParam()));
  for (int n = 0; n < 2; ++n) {
    const auto& sm = b.product.sync_managers.at(static_cast<std::size_t>(n));
    b.configure_sm(n, sm.start, sm.length, sm.control);
  }
  ASSERT_EQ(b.send(message(kCoE, 1, vendor_id_request())), 1);
  EXPECT_FALSE(b.receive().has_value());
  // Entering PreOp serves the request that waited in SM0.
  b.request_state(ecat::AlState::PreOp);
  auto r = b.receive();
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(u32_at(*r, 12), b.product.identity.vendor_id);
}

TEST_P(MailboxOnProduct, RepliesCarryCounters1To7) {
  Bench b(load(GetParam()));
  b.to_preop();
  std::vector<int> counters;
  for (int i = 0; i < 9; ++i) {
    auto r = b.exchange(kCoE, vendor_id_request());
    ASSERT_TRUE(r.has_value());
    counters.push_back((r->at(5) >> 4) & 7);
  }
  EXPECT_EQ(counters, (std::vector<int>{1, 2, 3, 4, 5, 6, 7, 1, 2}));
}

TEST_P(MailboxOnProduct, RepeatedCounterIsADuplicateAndIgnored) {
  Bench b(load(GetParam()));
  b.to_preop();
  ASSERT_EQ(b.send(message(kCoE, 3, vendor_id_request())), 1);
  ASSERT_TRUE(b.receive().has_value());
  ASSERT_EQ(b.send(message(kCoE, 3, vendor_id_request())), 1);
  EXPECT_FALSE(b.receive().has_value()) << "same counter: the master's retry, already served";
  ASSERT_EQ(b.send(message(kCoE, 4, vendor_id_request())), 1);
  EXPECT_TRUE(b.receive().has_value());
  // Counter 0 means "not counted": never a duplicate.
  ASSERT_EQ(b.send(message(kCoE, 0, vendor_id_request())), 1);
  EXPECT_TRUE(b.receive().has_value());
  ASSERT_EQ(b.send(message(kCoE, 0, vendor_id_request())), 1);
  EXPECT_TRUE(b.receive().has_value());
}

TEST_P(MailboxOnProduct, RepeatRequestSendsTheLastReplyAgain) {
  Bench b(load(GetParam()));
  b.to_preop();
  auto first = b.exchange(kCoE, vendor_id_request());
  ASSERT_TRUE(first.has_value());
  EXPECT_FALSE(b.receive().has_value());
  // The master lost it: toggle the repeat request (SM1 activate bit1).
  b.write(0x080E, {0x03});
  EXPECT_EQ(b.read(0x080F, 1)[0] & 0x02, 0x02) << "repeat ack follows the request";
  auto again = b.receive();
  ASSERT_TRUE(again.has_value());
  EXPECT_EQ(*again, *first);
  // Toggle back: the same reply once more, ack cleared.
  b.write(0x080E, {0x01});
  EXPECT_EQ(b.read(0x080F, 1)[0] & 0x02, 0x00);
  auto third = b.receive();
  ASSERT_TRUE(third.has_value());
  EXPECT_EQ(*third, *first);
}

TEST_P(MailboxOnProduct, RepliesQueueWhileSm1IsFull) {
  Bench b(load(GetParam()));
  b.to_preop();
  // Requests for 1018:01..04 without reading: one reply sits in SM1, the rest queue; once the
  // queue is full the request stays in SM0 and the next write is refused (working counter 0).
  const std::size_t slots = mailbox::MailboxModule::kReplySlots;
  std::uint8_t cnt = 0;
  for (std::size_t i = 0; i < slots + 2; ++i) {
    cnt = static_cast<std::uint8_t>(cnt >= 7 ? 1 : cnt + 1);
    ASSERT_EQ(b.send(message(kCoE, cnt, sdo_payload(0x40, 0x1018, static_cast<std::uint8_t>(1 + i % 4)))), 1)
        << "request " << i;
  }
  EXPECT_EQ(b.module.pending_replies(), slots);
  cnt = static_cast<std::uint8_t>(cnt >= 7 ? 1 : cnt + 1);
  EXPECT_EQ(b.send(message(kCoE, cnt, vendor_id_request())), 0) << "SM0 still holds a request";
  for (std::size_t i = 0; i < slots + 2; ++i) {
    auto r = b.receive();
    ASSERT_TRUE(r.has_value()) << "reply " << i;
    EXPECT_EQ(r->at(11), 1 + i % 4) << "replies in request order";
  }
  EXPECT_FALSE(b.receive().has_value());
}

// The ESC keeps SM1's event set once the master read the last message; the firmware masks it then
// (else a level-triggered PDI interrupt would never end) and unmasks it while a message waits.
TEST_P(MailboxOnProduct, Sm1EventIsUnmaskedOnlyWhileAMessageWaits) {
  constexpr std::uint32_t kSm1Event = 1u << 9;
  Bench b(load(GetParam()));
  b.to_preop();
  ASSERT_TRUE(b.exchange(kCoE, vendor_id_request()).has_value());
  EXPECT_NE(b.pdi.read_u32(reg::kAlEventRequest) & kSm1Event, 0u) << "the master read SM1";
  EXPECT_EQ(b.pdi.read_u32(reg::kAlEventMask) & kSm1Event, 0u) << "idle: masked";
  EXPECT_EQ(b.esc.pdi_irq(), 0u) << "no interrupt while idle";

  // Two requests: the first reply fills SM1, the second waits, so SM1's read must be seen.
  b.counter = 2;
  ASSERT_EQ(b.send(message(kCoE, 3, vendor_id_request())), 1);
  ASSERT_EQ(b.send(message(kCoE, 4, sdo_payload(0x40, 0x1018, 0x02))), 1);
  EXPECT_EQ(b.module.pending_replies(), 1u);
  EXPECT_NE(b.pdi.read_u32(reg::kAlEventMask) & kSm1Event, 0u) << "a reply waits: unmasked";
  ASSERT_TRUE(b.receive().has_value());   // reading SM1 interrupts the firmware: it sends the next
  auto second = b.receive();
  ASSERT_TRUE(second.has_value());
  EXPECT_EQ(second->at(11), 0x02);
  EXPECT_EQ(b.pdi.read_u32(reg::kAlEventMask) & kSm1Event, 0u) << "idle again";
  EXPECT_EQ(b.esc.pdi_irq(), 0u);
}

TEST_P(MailboxOnProduct, EmergenciesFromInitAreSentOnPreOpNewestEight) {
  Bench b(load(GetParam()));
  for (std::uint16_t i = 1; i <= 10; ++i) {
    ecat::coe::Emergency e;
    e.error_code = static_cast<std::uint16_t>(0xFF00 + i);
    e.error_register = 0x80;
    e.data[0] = static_cast<std::uint8_t>(i);
    b.module.post_emergency(e);
  }
  EXPECT_EQ(b.module.pending_emergencies(), 8u);
  b.to_preop();
  for (std::uint16_t i = 3; i <= 10; ++i) {
    auto r = b.receive();
    ASSERT_TRUE(r.has_value()) << "emergency " << i;
    EXPECT_EQ(u16_at(*r, 0), 10);
    EXPECT_EQ(r->at(5) & 0x0F, kCoE);
    EXPECT_EQ(u16_at(*r, 6) >> 12, 1) << "CoE service 1: emergency";
    EXPECT_EQ(u16_at(*r, 8), 0xFF00 + i);
    EXPECT_EQ(r->at(10), 0x80);
    EXPECT_EQ(r->at(11), i);
  }
  EXPECT_FALSE(b.receive().has_value());
}

TEST_P(MailboxOnProduct, BackToInitForgetsTheExchange) {
  Bench b(load(GetParam()));
  b.to_preop();
  ASSERT_EQ(b.send(message(kCoE, 5, vendor_id_request())), 1);
  b.request_state(ecat::AlState::Init);
  EXPECT_EQ(b.module.pending_replies(), 0u);
  b.request_state(ecat::AlState::PreOp);
  b.receive();  // whatever SM1 still held
  ASSERT_EQ(b.send(message(kCoE, 5, vendor_id_request())), 1);
  EXPECT_TRUE(b.receive().has_value()) << "the counter starts afresh after Init";
}

TEST_P(MailboxOnProduct, ExchangesAllocateNothing) {
  Bench b(load(GetParam()));
  b.to_preop();
  b.exchange(kCoE, vendor_id_request());  // warm-up
  // Frames built beforehand; the count covers the ESC, the module and the SDO server only.
  std::vector<std::vector<std::uint8_t>> writes, reads;
  for (int i = 0; i < 14; ++i) {
    const auto counter = static_cast<std::uint8_t>(2 + i % 6);
    std::vector<std::uint8_t> window(b.sm0_length(), 0);
    const auto m = message(kCoE, counter,
                           i % 2 ? vendor_id_request()
                                 : std::vector<std::uint8_t>{0x00, 0x80, 0x01, 0x00, 0x00, 0x00, 0x01, 0x00});
    std::copy(m.begin(), m.end(), window.begin());
    writes.push_back(b.pdu(0x02, b.sm0_start(), window));
    reads.push_back(b.pdu(0x01, b.sm1_start(), std::vector<std::uint8_t>(b.sm1_length(), 0)));
  }
  const long before = vdrive::test::allocation_count();
  for (std::size_t i = 0; i < writes.size(); ++i) {
    b.run(writes[i]);
    b.run(reads[i]);
  }
  EXPECT_EQ(vdrive::test::allocation_count() - before, 0);
  // And they were real exchanges: the last read frame carries a reply (working counter 1).
  EXPECT_EQ(reads.back()[reads.back().size() - 2], 1);
}

INSTANTIATE_TEST_SUITE_P(Products, MailboxOnProduct, ::testing::Values("a6b", "ds5c1", "ds1000a"));

}  // namespace
}  // namespace vdrive::firmware::mailbox_test
