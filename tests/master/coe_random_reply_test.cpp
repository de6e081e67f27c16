// Whatever a slave writes into SM1, the CoE client answers with a value, SdoAbort or
// MailboxError: never a crash, a hang or an out-of-bounds read (run under ASan/UBSan in the
// sanitizer build). The "slave" here reads each request from SM0 and answers with random bytes,
// sometimes a plausible CoE header with random fields.
#include <gtest/gtest.h>

#include <array>
#include <random>
#include <vector>

#include "master/coe.hpp"
#include "master/master.hpp"
#include "master/registers.hpp"
#include "tests/master/bare_esc_link.hpp"

namespace vdrive::master {
namespace {

TEST(CoeRandomReplies, ClientNeverFailsOtherThanByItsErrors) {
  test::BareEscLink line{"a6b"};
  Master master{line, line.clock()};
  ASSERT_EQ(master.scan(), 1u);
  for (std::size_t n = 0; n < 2; ++n) {
    const SmSetting& sm = master.slaves()[0].mailbox_sm[n];
    const std::array<std::uint8_t, 8> regs{static_cast<std::uint8_t>(sm.start), static_cast<std::uint8_t>(sm.start >> 8),
                                           static_cast<std::uint8_t>(sm.length), static_cast<std::uint8_t>(sm.length >> 8),
                                           sm.control, 0, sm.activate, 0};
    ASSERT_EQ(master.transport().fpwr(0x1001, static_cast<std::uint16_t>(reg::kSm0 + 8 * n), regs), 1);
  }
  master.set_mailbox_timeout(2'000'000);
  const SmSetting sm0 = master.slaves()[0].mailbox_sm[0], sm1 = master.slaves()[0].mailbox_sm[1];
  std::mt19937 rng(4242);
  esc::Esc& esc = line.esc();
  auto pdi8 = [&](std::uint16_t a) {
    std::uint8_t v = 0;
    esc.pdi_read(a, std::span(&v, 1));
    return v;
  };
  line.after_frame = [&] {
    if (pdi8(0x0805) & 0x08) {
      std::vector<std::uint8_t> req(sm0.length);
      esc.pdi_read(sm0.start, req);
      if (pdi8(0x080D) & 0x08) return;
      std::vector<std::uint8_t> reply(sm1.length);
      for (auto& b : reply) b = static_cast<std::uint8_t>(rng());
      const int kind = static_cast<int>(rng() % 4);
      if (kind > 0) {  // a CoE message of random length and service, maybe an SDO response
        const std::size_t len = rng() % (sm1.length - 5u);
        reply[0] = static_cast<std::uint8_t>(len);
        reply[1] = static_cast<std::uint8_t>(len >> 8);
        reply[5] = static_cast<std::uint8_t>(0x03 | ((rng() % 8) << 4));
        if (kind == 2) reply[7] = 0x30;  // SDO response
        if (kind == 3) reply[7] = 0x80;  // SDO information
      }
      esc.pdi_write(sm1.start, reply);
    }
  };
  SdoClient& sdo = master.sdo(0);
  int values = 0, aborts = 0, mailbox_errors = 0;
  for (int i = 0; i < 300; ++i) {
    try {
      switch (i % 4) {
        case 0: (void)sdo.upload(0x6041, 0); break;
        case 1: sdo.download(0x2000, 1, std::vector<std::uint8_t>(300, 0xAA)); break;
        case 2: (void)sdo.od_list(); break;
        default: (void)sdo.entry_description(0x1018, 1); break;
      }
      ++values;
    } catch (const SdoAbort&) {
      ++aborts;
    } catch (const MailboxError&) {
      ++mailbox_errors;
    }
  }
  EXPECT_EQ(values + aborts + mailbox_errors, 300);
  EXPECT_GT(mailbox_errors, 0) << "random replies are mostly not answers";
}

}  // namespace
}  // namespace vdrive::master
