// Injected mailbox faults (vdrive/firmware/mailbox/mailbox_faults.hpp) as the project master's
// CoE client meets them on a virtual line of real drives: a lost reply is brought back by the
// client's repeat request or, lost again, ends in its timeout; a duplicated reply is dropped by
// its counter; an injected abort code arrives as that SdoAbort. (The wrong toggle bit needs a
// segmented transfer, which none of the three products' dictionaries can make: it is tested on
// the mailbox bench with a test dictionary, tests/firmware/mailbox/mailbox_faults_test.cpp.)
#include <gtest/gtest.h>

#include <string>

#include "master/coe.hpp"
#include "master/master.hpp"
#include "tests/master/virtual_line.hpp"
#include "vdrive/firmware/mailbox/mailbox_module.hpp"

namespace vdrive::master {
namespace {

constexpr Nanos kTimeout = 20'000'000;

class MailboxFaults : public ::testing::Test {
protected:
  test::VirtualLine line{{"ds5c1", "ds1000a"}};
  Master master{line, line.clock()};
  void SetUp() override {
    ASSERT_EQ(master.scan(), 2u);
    master.set_mailbox_timeout(kTimeout);
    ASSERT_TRUE(master.request_state(AlState::PreOp));
  }
  firmware::mailbox::MailboxModule& mailbox(std::size_t i) { return line.network().firmware(i).mailbox(); }
  std::uint32_t vendor(std::size_t i) { return master.sdo(i).upload_value<std::uint32_t>(0x1018, 1); }
};

TEST_F(MailboxFaults, LostReplyIsBroughtBackByTheRepeatRequest) {
  const std::uint32_t expected = vendor(1);
  SdoClient& sdo = master.sdo(1);
  const std::uint64_t repeats = sdo.mailbox().repeat_requests();
  mailbox(1).set_faults({.lose_replies = 1});
  const Nanos start = line.clock().now();
  EXPECT_EQ(vendor(1), expected);
  EXPECT_EQ(sdo.mailbox().repeat_requests(), repeats + 1);
  EXPECT_GE(line.clock().now() - start, kTimeout) << "the client waited its timeout first";
  EXPECT_EQ(mailbox(1).faults().lose_replies, 0) << "used up";
  EXPECT_EQ(vendor(1), expected) << "and the mailbox goes on";
}

TEST_F(MailboxFaults, ReplyLostTwiceEndsInTheClientsTimeout) {
  const std::uint32_t expected = vendor(0);
  mailbox(0).set_faults({.lose_replies = 2});  // the reply and its resend
  const Nanos start = line.clock().now();
  try {
    vendor(0);
    ADD_FAILURE() << "no timeout";
  } catch (const MailboxError& e) {
    EXPECT_NE(std::string(e.what()).find("no mailbox reply"), std::string::npos) << e.what();
    EXPECT_EQ(e.code(), 0);
  }
  EXPECT_GE(line.clock().now() - start, 2 * kTimeout) << "timeout, repeat request, timeout";
  EXPECT_EQ(mailbox(0).faults().lose_replies, 0);
  EXPECT_EQ(vendor(0), expected) << "the next request is served";
}

TEST_F(MailboxFaults, DuplicatedReplyIsDroppedByItsCounter) {
  const std::uint32_t vendor_id = vendor(0);
  const std::uint32_t product = master.sdo(0).upload_value<std::uint32_t>(0x1018, 2);
  ASSERT_NE(vendor_id, product);
  mailbox(0).set_faults({.duplicate_replies = 1});
  EXPECT_EQ(vendor(0), vendor_id);
  EXPECT_EQ(mailbox(0).faults().duplicate_replies, 0);
  // The copy of the 1018h:01 reply waits in SM1 now; the client must not take it for 1018h:02.
  EXPECT_NE(line.network().esc(0).peek(0x080D) & 0x08, 0) << "the copy is in SM1";
  EXPECT_EQ(master.sdo(0).upload_value<std::uint32_t>(0x1018, 2), product);
  EXPECT_EQ(vendor(0), vendor_id);
}

TEST_F(MailboxFaults, InjectedAbortCodeReachesTheClientOnce) {
  mailbox(1).set_faults({.abort_code = 0x08000022});
  try {
    master.sdo(1).upload_value<std::uint32_t>(0x1018, 2);
    ADD_FAILURE() << "no abort";
  } catch (const SdoAbort& e) {
    EXPECT_EQ(e.code(), 0x08000022u);
    EXPECT_EQ(e.index(), 0x1018);
    EXPECT_EQ(e.subindex(), 2);
  }
  EXPECT_EQ(mailbox(1).faults().abort_code, 0u);
  // Downloads too, then served again.
  mailbox(1).set_faults({.abort_code = 0x06090030});
  try {
    master.sdo(1).download_value<std::uint32_t>(0x1C32, 2, 1'000'000);
    ADD_FAILURE() << "no abort";
  } catch (const SdoAbort& e) {
    EXPECT_EQ(e.code(), 0x06090030u);
    EXPECT_EQ(e.index(), 0x1C32);
  }
  EXPECT_NE(vendor(1), 0u);
}

TEST_F(MailboxFaults, MailboxSetUpAgainStartsTheReplyCounterAnew) {
  // Init and back: the slave's replies count from 1 again; the client must not take the first
  // as a copy of the last one it saw before.
  for (int round = 0; round < 3; ++round) {
    SCOPED_TRACE(round);
    EXPECT_NE(vendor(0), 0u);
    ASSERT_TRUE(master.request_state(AlState::Init));
    ASSERT_TRUE(master.request_state(AlState::PreOp));
  }
  EXPECT_NE(vendor(0), 0u);
}

}  // namespace
}  // namespace vdrive::master
