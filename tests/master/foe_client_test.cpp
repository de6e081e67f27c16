// The project master's FoE client against the slaves' own firmware on a virtual line, the way a
// field engineer updates a DS1000A-EC (FoE firmware download, L746-L752): Init -> Boot, write the
// image, Boot -> Init (restart), and 100Ah shows the new version. A lost ACK is recovered by
// sending the packet again, a lost frame with a DATA packet by the transport's retry (the drive
// drops the copy by its mailbox counter); refusals arrive as FoeError with the ETG.1000.6 code, products
// without FoE (A6B L656/L705, DS5C1 L2512) answer with the mailbox error "unsupported protocol",
// and the DS5C1 refuses Boot with AL status code 0013h (E-802, L7115). FoeClient::read runs against
// a stand-in slave (no product serves reads).
#include <gtest/gtest.h>

#include <stdlib.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "master/foe.hpp"
#include "master/master.hpp"
#include "master/registers.hpp"
#include "tests/master/bare_esc_link.hpp"
#include "tests/master/virtual_line.hpp"
#include "vdrive/firmware/foe/firmware_image.hpp"

namespace vdrive::master {
namespace {

// The drives keep their firmware under $VDRIVE_STATE_DIR: a fresh one per test, restored after.
class ScopedStateDir {
public:
  ScopedStateDir() {
    std::string pattern = (std::filesystem::temp_directory_path() / "vdrive-foe-XXXXXX").string();
    path = ::mkdtemp(pattern.data()) ? pattern : std::string();
    if (const char* old = std::getenv("VDRIVE_STATE_DIR")) previous = old;
    ::setenv("VDRIVE_STATE_DIR", path.c_str(), 1);
  }
  ~ScopedStateDir() {
    if (previous.empty()) ::unsetenv("VDRIVE_STATE_DIR");
    else ::setenv("VDRIVE_STATE_DIR", previous.c_str(), 1);
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  std::string path, previous;
};

std::vector<std::uint8_t> image(const std::string& version, std::size_t payload_bytes) {
  std::vector<std::uint8_t> payload(payload_bytes);
  for (std::size_t i = 0; i < payload.size(); ++i) payload[i] = static_cast<std::uint8_t>(i ^ 0x5A);
  const std::string img = firmware::foe::make_image("DS1000A-EC", version, payload);
  return {img.begin(), img.end()};
}

std::string version_of(Master& master, std::size_t slave) {
  const auto bytes = master.sdo(slave).upload(0x100A, 0);
  std::string s(bytes.begin(), bytes.end());
  return s.substr(0, s.find('\0'));
}

FoeOptions fast() {
  FoeOptions o;
  o.timeout = 20'000'000;
  return o;
}

class FoeOnLine : public ::testing::Test {
protected:
  ScopedStateDir state;
  test::VirtualLine line{{"a6b", "ds5c1", "ds1000a"}};
  Master master{line, line.clock()};
  static constexpr std::size_t kA6b = 0, kDs5c1 = 1, kDs1000a = 2;
  void SetUp() override {
    ASSERT_EQ(master.scan(), 3u);
    master.set_mailbox_timeout(20'000'000);
  }
};

const std::string kName = "ECATFW__DS1000A-EC_V1.10.efw";

TEST_F(FoeOnLine, FirmwareDownloadThroughBootChangesTheVersion) {
  ASSERT_TRUE(master.request_state(kDs1000a, AlState::PreOp));
  EXPECT_EQ(version_of(master, kDs1000a), "V1.00/1.00");
  ASSERT_TRUE(master.request_state(kDs1000a, AlState::Boot));
  FoeClient foe(master, kDs1000a, fast());
  EXPECT_EQ(foe.max_data(), 128u - 12u) << "bootstrap mailbox 128 bytes (SII words 14h-17h)";
  std::size_t reported = 0;
  const std::vector<std::uint8_t> file = image("V1.10/1.00", 2000);
  FoeOptions with_progress = fast();
  with_progress.progress = [&](std::size_t done, std::size_t total) {
    EXPECT_EQ(total, file.size());
    reported = done;
  };
  FoeClient observed(master, kDs1000a, with_progress);
  observed.write(kName, file);
  EXPECT_EQ(reported, file.size());
  EXPECT_EQ(observed.resent_packets(), 0u);
  ASSERT_TRUE(master.request_state(kDs1000a, AlState::Init));  // Boot -> Init: the drive restarts
  ASSERT_TRUE(master.request_state(kDs1000a, AlState::PreOp));
  EXPECT_EQ(version_of(master, kDs1000a), "V1.10/1.00");
  EXPECT_TRUE(std::filesystem::exists(state.path + "/ds1000a-00000000.firmware"));
}

TEST_F(FoeOnLine, LostAckIsRecoveredBySendingThePacketAgain) {
  ASSERT_TRUE(master.request_state(kDs1000a, AlState::Boot));
  // Lose the frames that bring ACK 2 back: the first read and the one after the mailbox repeat.
  int dropped = 0;
  line.drop_reply = [&](std::span<const std::uint8_t> frame) {
    static const std::uint8_t ack2[] = {0x04, 0x00, 0x02, 0x00, 0x00, 0x00};
    for (std::size_t i = 6; i + sizeof(ack2) <= frame.size(); ++i) {
      if (frame[i - 6] == 6 && frame[i - 5] == 0 && (frame[i - 1] & 0x0F) == 4 &&
          std::equal(std::begin(ack2), std::end(ack2), frame.begin() + static_cast<std::ptrdiff_t>(i)) && dropped < 2) {
        ++dropped;
        return true;
      }
    }
    return false;
  };
  FoeClient foe(master, kDs1000a, fast());
  foe.write(kName, image("V1.11/1.00", 500));
  EXPECT_EQ(dropped, 2);
  EXPECT_EQ(foe.resent_packets(), 1u) << "packet 2 sent again, acknowledged again";
  EXPECT_GE(foe.mailbox().repeat_requests(), 1u);
  line.drop_reply = nullptr;
  ASSERT_TRUE(master.request_state(kDs1000a, AlState::Init));
  ASSERT_TRUE(master.request_state(kDs1000a, AlState::PreOp));
  EXPECT_EQ(version_of(master, kDs1000a), "V1.11/1.00") << "the image arrived whole, packet 2 once";
}

// DATA 2 reaches the drive but the frame carrying it is lost on its way back: the transport sends
// the same frame again (same mailbox counter), the drive drops the copy as a repeated message
// (ETG.1000.4) and the download goes on with packet 3.
TEST_F(FoeOnLine, LostDataFrameIsSentAgainAndTakenOnce) {
  ASSERT_TRUE(master.request_state(kDs1000a, AlState::Boot));
  int dropped = 0;
  line.drop_reply = [&](std::span<const std::uint8_t> frame) {
    static const std::uint8_t data2[] = {0x03, 0x00, 0x02, 0x00, 0x00, 0x00};
    for (std::size_t i = 6; i + sizeof(data2) <= frame.size(); ++i) {
      if ((frame[i - 1] & 0x0F) == 4 && std::equal(std::begin(data2), std::end(data2), frame.begin() + static_cast<std::ptrdiff_t>(i)) &&
          dropped < 1) {
        ++dropped;
        return true;
      }
    }
    return false;
  };
  const std::uint64_t timeouts = master.transport().timeouts();
  FoeClient foe(master, kDs1000a, fast());
  foe.write(kName, image("V1.12/1.00", 500));
  EXPECT_EQ(dropped, 1);
  EXPECT_GE(master.transport().timeouts(), timeouts + 1) << "the frame with DATA 2 was sent again";
  EXPECT_EQ(foe.resent_packets(), 0u) << "the drive acknowledged the first copy";
  line.drop_reply = nullptr;
  ASSERT_TRUE(master.request_state(kDs1000a, AlState::Init));
  ASSERT_TRUE(master.request_state(kDs1000a, AlState::PreOp));
  EXPECT_EQ(version_of(master, kDs1000a), "V1.12/1.00") << "packet 2 stored once";
}

// Every client of one slave continues the slave's mailbox counter: a new client starting again at
// 1 after a message with counter 1 would be dropped by the slave as a repeat and left waiting.
TEST_F(FoeOnLine, ClientsOfOneSlaveContinueItsMailboxCounter) {
  ASSERT_TRUE(master.request_state(kDs1000a, AlState::PreOp));
  EXPECT_EQ(version_of(master, kDs1000a), "V1.00/1.00");  // CoE client: counter 1
  for (int i = 0; i < 9; ++i) {  // FoE clients, one message each: counters 2, 3, ... 7, 1, 2, 3
    FoeClient foe(master, kDs1000a, fast());
    try {
      foe.write(kName, image("V1.10/1.00", 10));
      ADD_FAILURE() << "firmware accepted in Pre-Op";
    } catch (const FoeError& e) {
      EXPECT_EQ(e.code(), 0x8008u) << i;
    }
    EXPECT_EQ(foe.mailbox().repeat_requests(), 0u) << i << ": the slave answered at once";
  }
  EXPECT_EQ(version_of(master, kDs1000a), "V1.00/1.00") << "and the CoE client goes on after them";
}

TEST_F(FoeOnLine, RefusalsArriveAsFoeErrors) {
  ASSERT_TRUE(master.request_state(kDs1000a, AlState::PreOp));
  try {
    FoeClient(master, kDs1000a, fast()).write(kName, image("V1.10/1.00", 10));
    ADD_FAILURE() << "firmware accepted in Pre-Op";
  } catch (const FoeError& e) {
    EXPECT_EQ(e.code(), 0x8008u);
    EXPECT_EQ(e.slave_text(), "Bootstrap only");
  }
  ASSERT_TRUE(master.request_state(kDs1000a, AlState::Boot));
  // (A password is refused only with the SSC's checks, foe_strict_firmware_check: foe_download_test.)
  try {
    FoeClient(master, kDs1000a, fast()).read(kName);
    ADD_FAILURE() << "read served";
  } catch (const FoeError& e) {
    EXPECT_EQ(e.code(), 0x8001u);
  }
}

TEST_F(FoeOnLine, ProductsWithoutFoeAnswerWithAMailboxError) {
  ASSERT_TRUE(master.request_state(kA6b, AlState::Boot)) << "A6B: Boot is legal (L33038-L33062)";
  try {
    FoeClient(master, kA6b, fast()).write(kName, image("V1.10/1.00", 10));
    ADD_FAILURE() << "A6B took FoE";
  } catch (const FoeError&) {
    ADD_FAILURE() << "A6B answered FoE";
  } catch (const MailboxError& e) {
    EXPECT_EQ(e.code(), 0x0002) << "unsupported protocol";
  }
  ASSERT_TRUE(master.request_state(kDs5c1, AlState::PreOp));
  try {
    FoeClient(master, kDs5c1, fast()).write(kName, image("V1.10/1.00", 10));
    ADD_FAILURE() << "DS5C1 took FoE";
  } catch (const MailboxError& e) {
    EXPECT_EQ(e.code(), 0x0002);
  }
}

TEST_F(FoeOnLine, Ds5c1RefusesBootWith0013) {
  ASSERT_TRUE(master.request_state(kDs5c1, AlState::Init));
  EXPECT_FALSE(master.request_state(kDs5c1, AlState::Boot));
  EXPECT_EQ(master.slaves()[kDs5c1].al.status_code, 0x0013) << "E-802 (L7115)";
  EXPECT_EQ(master.slaves()[kDs5c1].state(), AlState::Init);
}

// ---- read --------------------------------------------------------------------------------------
// No product serves FoE reads (the DS1000A-EC documents download only and answers 0x8001), so
// FoeClient::read runs against a stand-in written from ETG.1000.6 5.7 on a bare ESC's SM0/SM1:
// RRQ -> DATA 1; ACK n -> DATA n+1 of up to (SM1 length - 12) bytes; a shorter one ends the file
// (an empty one after a file of whole packets).
class FoeReadServer {
public:
  FoeReadServer(esc::Esc& esc, std::vector<std::uint8_t> file) : esc_(esc), file_(std::move(file)) {}
  std::uint32_t password = 0;
  std::string name;
  std::uint64_t acks = 0;
  bool finished = false;

  void service() {
    const std::uint16_t sm0_start = u16(0x0800), sm0_len = u16(0x0802);
    const std::uint16_t sm1_start = u16(0x0808), sm1_len = u16(0x080A);
    if (!(u8(0x0806) & 1) || !(u8(0x080E) & 1) || sm0_len < 16 || sm1_len < 16) return;
    if (u8(0x0805) & 0x08) {  // SM0 full: read it whole, which hands it back
      std::vector<std::uint8_t> m(sm0_len);
      esc_.pdi_read(sm0_start, m);
      const std::size_t length = static_cast<std::size_t>(m[0] | (m[1] << 8));
      const std::uint8_t op = m[6];
      const std::uint32_t field = u32(m, 8);
      if ((m[5] & 0x0F) == 4 && op == 1) {  // RRQ
        password = field;
        name.assign(m.begin() + 12, m.begin() + 6 + static_cast<std::ptrdiff_t>(length));
        packet_ = 0;
        at_ = 0;
        queue_data(sm1_len);
      } else if ((m[5] & 0x0F) == 4 && op == 4 && field == packet_) {  // ACK of our last DATA
        ++acks;
        if (last_sent_) finished = true;
        else queue_data(sm1_len);
      }
    }
    if (!out_.empty() && !(u8(0x080D) & 0x08)) {
      esc_.pdi_write(sm1_start, out_);  // the whole buffer: its last byte hands it to the master
      out_.clear();
    }
  }

private:
  void queue_data(std::uint16_t sm1_len) {
    const std::size_t full = sm1_len - 12u;
    const std::size_t n = std::min(full, file_.size() - at_);
    ++packet_;
    counter_ = static_cast<std::uint8_t>(counter_ % 7 + 1);
    out_.assign(sm1_len, 0);
    out_[0] = static_cast<std::uint8_t>(6 + n);
    out_[1] = static_cast<std::uint8_t>((6 + n) >> 8);
    out_[5] = static_cast<std::uint8_t>(4 | (counter_ << 4));
    out_[6] = 3;  // DATA
    for (int i = 0; i < 4; ++i) out_[8 + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(packet_ >> (8 * i));
    std::copy_n(file_.begin() + static_cast<std::ptrdiff_t>(at_), n, out_.begin() + 12);
    at_ += n;
    last_sent_ = n < full;
  }
  std::uint8_t u8(std::uint16_t a) {
    std::uint8_t v = 0;
    esc_.pdi_read(a, std::span(&v, 1));
    return v;
  }
  std::uint16_t u16(std::uint16_t a) { return static_cast<std::uint16_t>(u8(a) | (u8(static_cast<std::uint16_t>(a + 1)) << 8)); }
  static std::uint32_t u32(const std::vector<std::uint8_t>& p, std::size_t at) {
    return static_cast<std::uint32_t>(p[at] | (p[at + 1] << 8) | (p[at + 2] << 16)) | (static_cast<std::uint32_t>(p[at + 3]) << 24);
  }

  esc::Esc& esc_;
  std::vector<std::uint8_t> file_;
  std::vector<std::uint8_t> out_;
  std::size_t at_ = 0;
  std::uint32_t packet_ = 0;
  bool last_sent_ = false;
  std::uint8_t counter_ = 0;
};

class FoeRead : public ::testing::TestWithParam<std::size_t> {};

TEST_P(FoeRead, ReadsTheFileAndAcknowledgesEveryPacket) {
  test::BareEscLink line{"a6b"};
  Master master{line, line.clock()};
  ASSERT_EQ(master.scan(), 1u);
  for (std::size_t n = 0; n < 2; ++n) {  // no firmware behind this ESC: enable SM0/SM1 as for Pre-Op
    const SmSetting& sm = master.slaves()[0].mailbox_sm[n];
    const std::array<std::uint8_t, 8> regs{static_cast<std::uint8_t>(sm.start), static_cast<std::uint8_t>(sm.start >> 8),
                                           static_cast<std::uint8_t>(sm.length), static_cast<std::uint8_t>(sm.length >> 8),
                                           sm.control, 0, sm.activate, 0};
    ASSERT_EQ(master.transport().fpwr(0x1001, static_cast<std::uint16_t>(reg::kSm0 + 8 * n), regs), 1);
  }
  const std::size_t full = master.slaves()[0].mailbox_sm[1].length - 12u;
  const std::size_t size = GetParam() == 0 ? 2 * full : GetParam();  // 0: whole packets
  std::vector<std::uint8_t> file(size);
  for (std::size_t i = 0; i < file.size(); ++i) file[i] = static_cast<std::uint8_t>(i * 13 + 1);
  FoeReadServer server(line.esc(), file);
  line.after_frame = [&] { server.service(); };
  FoeClient foe(master, 0, fast());
  EXPECT_EQ(foe.read("log.txt", 0x1234), file);
  EXPECT_EQ(server.name, "log.txt");
  EXPECT_EQ(server.password, 0x1234u);
  EXPECT_TRUE(server.finished) << "the last packet acknowledged too";
  EXPECT_EQ(server.acks, size / full + 1) << "every DATA packet, the empty last one included";
}

INSTANTIATE_TEST_SUITE_P(FoeFileSizes, FoeRead, ::testing::Values(std::size_t{600}, std::size_t{0}, std::size_t{5}));

}  // namespace
}  // namespace vdrive::master
