// The project master's FoE client against the slaves' own firmware on a virtual line, the way a
// field engineer updates a DS1000A-EC (FoE firmware download, L746-L752): Init -> Boot, write the
// image, Boot -> Init (restart), and 100Ah shows the new version. A lost ACK is recovered by
// sending the packet again; refusals arrive as FoeError with the ETG.1000.6 code, products
// without FoE (A6B L656/L705, DS5C1 L2512) answer with the mailbox error "unsupported protocol",
// and the DS5C1 refuses Boot with AL status code 0013h (E-802, L7115).
#include <gtest/gtest.h>

#include <stdlib.h>

#include <filesystem>
#include <string>
#include <vector>

#include "master/foe.hpp"
#include "master/master.hpp"
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
  try {
    FoeClient(master, kDs1000a, fast()).write(kName, image("V1.10/1.00", 10), 1234);
    ADD_FAILURE() << "password accepted";
  } catch (const FoeError& e) {
    EXPECT_EQ(e.code(), 0x800Au);
  }
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

}  // namespace
}  // namespace vdrive::master
