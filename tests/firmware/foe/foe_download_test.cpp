// FoE firmware download through the mailbox (ETG.1000.6 5.7) as a master drives it over SM0/SM1:
// the DS1000A-EC takes a firmware file in Boot ("Firmware Download 対応", L746-L752) with the ETG
// slave-stack defaults we chose (docs/foe.md, docs/profiles.md); the A6B (FoE unsupported, L656,
// L705) and the DS5C1 (mailbox type 04h "FoE (未对应)", L2512) answer FoE with the mailbox error
// "unsupported protocol". Expected codes are ETG.1000.6's FoE error table, written out here.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "tests/firmware/coe_test_client.hpp"
#include "tests/firmware/mailbox_test_bench.hpp"
#include "vdrive/firmware/coe/parameter_store.hpp"
#include "vdrive/firmware/foe/firmware_image.hpp"
#include "tests/support/allocation_counter.hpp"


namespace vdrive::firmware::mailbox_test {
namespace {

constexpr std::uint8_t kFoE = 4;
constexpr std::uint8_t kRrq = 1, kWrq = 2, kData = 3, kAck = 4, kErr = 5;

std::vector<std::uint8_t> foe(std::uint8_t op, std::uint32_t field, std::vector<std::uint8_t> tail = {}) {
  std::vector<std::uint8_t> p{op, 0};
  const std::vector<std::uint8_t> f = le(field, 4);
  p.insert(p.end(), f.begin(), f.end());
  p.insert(p.end(), tail.begin(), tail.end());
  return p;
}
std::vector<std::uint8_t> text(const std::string& s) { return {s.begin(), s.end()}; }

struct FoeReply {
  std::uint8_t op = 0;
  std::uint32_t field = 0;  // packet number or error code
};
FoeReply foe_reply(const std::optional<std::vector<std::uint8_t>>& r) {
  if (!r) {
    ADD_FAILURE() << "no reply";
    return {};
  }
  EXPECT_EQ(r->at(5) & 0x0F, kFoE) << "an FoE reply";
  return {r->at(6), u32_at(*r, 8)};
}

profile::ProductProfile ds1000a() { return profile::load_profile("ds1000a"); }
// With the ETG SSC's checks (ECATFW__ name, password 0) and vdrive's image format: the option
// (`foe_strict_firmware_check`, `vdrive run --foe-strict`) for testing a master's error handling.
profile::ProductProfile ds1000a_strict() {
  profile::ProductProfile p = ds1000a();
  p.foe_strict_firmware_check = true;
  return p;
}

// Init -> Boot with the SII's bootstrap mailbox (128 bytes at 1000h/1080h, profile.yaml).
void to_boot(Bench& b) {
  b.configure_sm(0, *b.product.mailbox.boot_rx_offset, *b.product.mailbox.boot_rx_size, 0x26);
  b.configure_sm(1, *b.product.mailbox.boot_tx_offset, *b.product.mailbox.boot_tx_size, 0x22);
  b.request_state(ecat::AlState::Boot);
  ASSERT_EQ(b.esm.state(), ecat::AlState::Boot);
}

std::string version_object(Bench& b) {
  const od::EntryDesc* e = b.dictionary.find(0x100A, 0);
  const auto raw = b.objects.raw(*e);
  std::string s(raw.begin(), raw.end());
  return s.substr(0, s.find('\0'));
}

std::vector<std::uint8_t> image(const std::string& product, const std::string& version, std::size_t payload_bytes) {
  std::vector<std::uint8_t> payload(payload_bytes);
  for (std::size_t i = 0; i < payload.size(); ++i) payload[i] = static_cast<std::uint8_t>(i * 7 + 3);
  const std::string img = foe::make_image(product, version, payload);
  return {img.begin(), img.end()};
}

// Sends `file` as DATA packets 1.. of (SM0 length - 12) bytes; returns the reply to the last one.
FoeReply send_file(Bench& b, const std::vector<std::uint8_t>& file, std::uint32_t first_packet = 1) {
  const std::size_t full = b.sm0_length() - 12u;
  std::size_t at = 0;
  std::uint32_t packet = first_packet;
  for (;;) {
    const std::size_t n = std::min(full, file.size() - at);
    const FoeReply r = foe_reply(b.exchange(kFoE, foe(kData, packet, {file.begin() + static_cast<std::ptrdiff_t>(at),
                                                                       file.begin() + static_cast<std::ptrdiff_t>(at + n)})));
    at += n;
    if (r.op != kAck || r.field != packet || n < full) return r;
    ++packet;
  }
}

const std::string kName = "ECATFW__DS1000A-EC_V1.10.efw";

TEST(FoeDownload, CompleteDownloadInBootChangesTheVersionAfterTheRestart) {
  TempDir state;
  {
    Bench b(ds1000a(), {}, state.path);
    ASSERT_EQ(version_object(b), "V1.00/1.00");  // factory 100Ah (profile; form "Vn.nn/m.mm", L4439)
    to_boot(b);
    const FoeReply wrq = foe_reply(b.exchange(kFoE, foe(kWrq, 0, text(kName))));
    EXPECT_EQ(wrq.op, kAck);
    EXPECT_EQ(wrq.field, 0u) << "WRQ is acknowledged with packet 0";
    const std::vector<std::uint8_t> file = image("DS1000A-EC", "V1.10/1.00", 1000);
    const FoeReply last = send_file(b, file);
    EXPECT_EQ(last.op, kAck);
    EXPECT_EQ(last.field, (file.size() + 115) / 116) << "every packet of 116 bytes (128 - 12) acknowledged";
    EXPECT_EQ(version_object(b), "V1.00/1.00") << "the new firmware runs only after the restart";
    b.request_state(ecat::AlState::Init);  // Boot -> Init restarts the drive
    EXPECT_EQ(version_object(b), "V1.10/1.00");
    const std::string stored = state.path + "/ds1000a-00000000.firmware";
    ASSERT_TRUE(std::filesystem::exists(stored));
    EXPECT_EQ(std::filesystem::file_size(stored), file.size());
  }
  Bench powered_again(ds1000a(), {}, state.path);
  EXPECT_EQ(version_object(powered_again), "V1.10/1.00") << "the image is in the drive's flash";
}

TEST(FoeDownload, FileOfWholePacketsEndsWithAnEmptyPacket) {
  TempDir state;
  Bench b(ds1000a(), {}, state.path);
  to_boot(b);
  ASSERT_EQ(foe_reply(b.exchange(kFoE, foe(kWrq, 0, text(kName)))).op, kAck);
  // 48-byte header + 184 bytes = 232 = 2 x 116: both packets are full, so neither ends the file;
  // a third, empty packet does (ETG.1000.6: a packet shorter than the mailbox allows is the last).
  const std::vector<std::uint8_t> file = image("DS1000A-EC", "V2.03/1.00", 184);
  ASSERT_EQ(file.size(), 232u);
  const std::string stored = state.path + "/ds1000a-00000000.firmware";
  for (std::uint32_t packet = 1; packet <= 2; ++packet) {
    const auto at = file.begin() + static_cast<std::ptrdiff_t>((packet - 1) * 116);
    const FoeReply r = foe_reply(b.exchange(kFoE, foe(kData, packet, {at, at + 116})));
    EXPECT_EQ(r.op, kAck) << packet;
    EXPECT_EQ(r.field, packet);
  }
  EXPECT_FALSE(std::filesystem::exists(stored)) << "two full packets: the file is not complete yet";
  const FoeReply end = foe_reply(b.exchange(kFoE, foe(kData, 3)));
  EXPECT_EQ(end.op, kAck);
  EXPECT_EQ(end.field, 3u);
  EXPECT_TRUE(std::filesystem::exists(stored)) << "the empty packet ended the file: image programmed";
  EXPECT_EQ(version_object(b), "V1.00/1.00");
  b.request_state(ecat::AlState::Init);
  EXPECT_EQ(version_object(b), "V2.03/1.00");
}

TEST(FoeDownload, RepeatedPacketIsAcknowledgedAgainAndStoredOnce) {
  Bench b(ds1000a());
  to_boot(b);
  ASSERT_EQ(foe_reply(b.exchange(kFoE, foe(kWrq, 0, text(kName)))).op, kAck);
  const std::vector<std::uint8_t> file = image("DS1000A-EC", "V1.20/1.00", 300);  // 348 bytes: 116 + 116 + 116
  const std::vector<std::uint8_t> first(file.begin(), file.begin() + 116);
  for (int attempt = 0; attempt < 2; ++attempt) {  // the master lost our ACK and sends packet 1 again
    const FoeReply r = foe_reply(b.exchange(kFoE, foe(kData, 1, first)));
    EXPECT_EQ(r.op, kAck) << attempt;
    EXPECT_EQ(r.field, 1u) << attempt;
  }
  const std::vector<std::uint8_t> rest(file.begin() + 116, file.end());
  const FoeReply last = send_file(b, rest, 2);
  EXPECT_EQ(last.op, kAck);
  const FoeReply end = foe_reply(b.exchange(kFoE, foe(kData, 4)));  // 348 = 3 full packets
  EXPECT_EQ(end.op, kAck) << "the image checks out: packet 1 was not stored twice";
  b.request_state(ecat::AlState::Init);
  EXPECT_EQ(version_object(b), "V1.20/1.00");
}

TEST(FoeDownload, WrongPacketNumberIs8005AndEndsTheTransfer) {
  Bench b(ds1000a());
  to_boot(b);
  ASSERT_EQ(foe_reply(b.exchange(kFoE, foe(kWrq, 0, text(kName)))).op, kAck);
  const std::vector<std::uint8_t> chunk(116, 0x55);
  ASSERT_EQ(foe_reply(b.exchange(kFoE, foe(kData, 1, chunk))).op, kAck);
  const FoeReply skipped = foe_reply(b.exchange(kFoE, foe(kData, 3, chunk)));
  EXPECT_EQ(skipped.op, kErr);
  EXPECT_EQ(skipped.field, 0x8005u) << "packet number wrong";
  const FoeReply after = foe_reply(b.exchange(kFoE, foe(kData, 2, chunk)));
  EXPECT_EQ(after.op, kErr);
  EXPECT_EQ(after.field, 0x8004u) << "no transfer any more: illegal";
}

TEST(FoeDownload, FileBeyond256KiBIsDiskFull8003) {
  Bench b(ds1000a());
  to_boot(b);
  ASSERT_EQ(foe_reply(b.exchange(kFoE, foe(kWrq, 0, text(kName)))).op, kAck);
  // 256 KiB + 1 = 2259 full packets of 116 bytes + 101: the short packet 2260 no longer fits.
  const std::vector<std::uint8_t> file = image("DS1000A-EC", "V1.30/1.00", 256 * 1024 + 1 - 48);
  const FoeReply r = send_file(b, file);
  EXPECT_EQ(r.op, kErr);
  EXPECT_EQ(r.field, 0x8003u) << "disk full";
  const FoeReply after = foe_reply(b.exchange(kFoE, foe(kData, 2261)));
  EXPECT_EQ(after.field, 0x8004u) << "the error ended the transfer";
  b.request_state(ecat::AlState::Init);
  EXPECT_EQ(version_object(b), "V1.00/1.00");
}

TEST(FoeDownload, FileOfExactly256KiBIsTaken) {
  Bench b(ds1000a());
  to_boot(b);
  ASSERT_EQ(foe_reply(b.exchange(kFoE, foe(kWrq, 0, text(kName)))).op, kAck);
  const std::vector<std::uint8_t> file = image("DS1000A-EC", "V1.30/1.00", 256 * 1024 - 48);
  const FoeReply r = send_file(b, file);
  EXPECT_EQ(r.op, kAck);
  EXPECT_EQ(r.field, 2260u) << "2259 full packets + 100 bytes";
  b.request_state(ecat::AlState::Init);
  EXPECT_EQ(version_object(b), "V1.30/1.00");
}

TEST(FoeDownload, StrictOtherFileNameIs8009InBootAnd8002Outside) {
  Bench b(ds1000a_strict());
  to_boot(b);
  const FoeReply in_boot = foe_reply(b.exchange(kFoE, foe(kWrq, 0, text("DS1000A-EC_V1.10.efw"))));
  EXPECT_EQ(in_boot.op, kErr);
  EXPECT_EQ(in_boot.field, 0x8009u) << "SSC: not a file for Bootstrap";
  b.request_state(ecat::AlState::Init);
  b.to_preop();
  const FoeReply in_preop = foe_reply(b.exchange(kFoE, foe(kWrq, 0, text("parameters.bin"))));
  EXPECT_EQ(in_preop.op, kErr);
  EXPECT_EQ(in_preop.field, 0x8002u) << "access denied: the drive keeps no other files";
}

TEST(FoeDownload, StrictPasswordOtherThanZeroIs800A) {
  Bench b(ds1000a_strict());
  to_boot(b);
  const FoeReply r = foe_reply(b.exchange(kFoE, foe(kWrq, 0x12345678, text(kName))));
  EXPECT_EQ(r.op, kErr);
  EXPECT_EQ(r.field, 0x800Au) << "no rights";
}

// The manual names no file, password or format (L746-L752): by default the drive takes whatever a
// master sends in Boot, kept as given; its size and CRC-32 are reported (last_download()).
TEST(FoeDownload, AnyFileIsTakenInBootByDefault) {
  TempDir state;
  Bench b(ds1000a(), {}, state.path);
  to_boot(b);
  const FoeReply wrq = foe_reply(b.exchange(kFoE, foe(kWrq, 0x12345678, text("fw.bin"))));
  ASSERT_EQ(wrq.op, kAck) << "any name and password";
  std::vector<std::uint8_t> file(64 * 1024);
  for (std::size_t i = 0; i < file.size(); ++i) file[i] = static_cast<std::uint8_t>(i * 13 + i / 256);
  const FoeReply last = send_file(b, file);
  EXPECT_EQ(last.op, kAck);
  EXPECT_EQ(last.field, file.size() / 116 + 1) << "564 packets of 116 bytes and one of 112";
  ASSERT_NE(b.module.foe(), nullptr);
  EXPECT_EQ(b.module.foe()->last_download().bytes, file.size());
  EXPECT_EQ(b.module.foe()->last_download().crc32, coe::crc32(file.data(), file.size()));
  const std::string stored = state.path + "/ds1000a-00000000.firmware";
  ASSERT_TRUE(std::filesystem::exists(stored));
  EXPECT_EQ(std::filesystem::file_size(stored), file.size()) << "the image as given";
  b.request_state(ecat::AlState::Init);
  EXPECT_EQ(version_object(b), "V1.00/1.00") << "a foreign image's version is unknown: the factory text";
}

TEST(FoeDownload, StrictRefusesTheSameFile) {
  Bench b(ds1000a_strict());
  to_boot(b);
  const FoeReply r = foe_reply(b.exchange(kFoE, foe(kWrq, 0, text("fw.bin"))));
  EXPECT_EQ(r.op, kErr);
  EXPECT_EQ(r.field, 0x8009u) << "SSC: not a file for Bootstrap";
  ASSERT_EQ(foe_reply(b.exchange(kFoE, foe(kWrq, 0, text(kName)))).op, kAck);
  const FoeReply content = send_file(b, std::vector<std::uint8_t>(64 * 1024, 0x5A));
  EXPECT_EQ(content.op, kErr);
  EXPECT_EQ(content.field, 0x800Du) << "not a vdrive image";
}

TEST(FoeDownload, AnyNameOutsideBootIs8008ByDefault) {
  Bench b(ds1000a());
  b.to_preop();
  const FoeReply r = foe_reply(b.exchange(kFoE, foe(kWrq, 0, text("fw.bin"))));
  EXPECT_EQ(r.op, kErr);
  EXPECT_EQ(r.field, 0x8008u) << "firmware download in Boot only";
}

TEST(FoeDownload, FirmwareOutsideBootIs8008BootstrapOnly) {
  Bench b(ds1000a());
  b.to_preop();
  for (const ecat::AlState state : {ecat::AlState::PreOp, ecat::AlState::SafeOp, ecat::AlState::Op}) {
    SCOPED_TRACE(static_cast<int>(state));
    b.request_state(state);
    ASSERT_EQ(b.esm.state(), state);
    const auto reply = b.exchange(kFoE, foe(kWrq, 0, text(kName)));
    const FoeReply r = foe_reply(reply);
    EXPECT_EQ(r.op, kErr);
    EXPECT_EQ(r.field, 0x8008u) << "bootstrap only";
    ASSERT_TRUE(reply.has_value());
    const std::string message(reply->begin() + 12, reply->end());
    EXPECT_EQ(message, "Bootstrap only") << "error text (ETG.1000.6)";
    const FoeReply data = foe_reply(b.exchange(kFoE, foe(kData, 1, std::vector<std::uint8_t>(116, 0))));
    EXPECT_EQ(data.field, 0x8004u) << "no transfer was opened";
  }
}

TEST(FoeDownload, NoFoeInInit) {
  // In Init the mailbox does not run: a request stays unanswered (ETG.1000.6: mailbox from Pre-Op/Boot).
  Bench b(ds1000a());
  b.configure_sm(0, b.sm0_start(), b.sm0_length(), 0x26);
  b.configure_sm(1, b.sm1_start(), b.sm1_length(), 0x22);
  ASSERT_EQ(b.esm.state(), ecat::AlState::Init);
  b.send(message(kFoE, 1, foe(kWrq, 0, text(kName))));
  EXPECT_FALSE(b.receive().has_value());
}

TEST(FoeDownload, StrictForeignOrDamagedImageIsRefusedAndTheOldVersionStays) {
  struct Case {
    std::vector<std::uint8_t> file;
    std::uint32_t code;
  };
  std::vector<std::uint8_t> damaged = image("DS1000A-EC", "V1.10/1.00", 500);
  damaged[300] ^= 0xFF;
  std::vector<std::uint8_t> cut = image("DS1000A-EC", "V1.10/1.00", 500);
  cut.resize(400);
  const std::vector<Case> cases{
      {image("DS5C1", "V1.10/1.00", 500), 0x800D},            // another product's image
      {image("DS1000A-EC", "1.10", 500), 0x800D},             // not the 100Ah form
      {std::vector<std::uint8_t>(500, 0x00), 0x800D},          // not an image at all
      {damaged, 0x800C},                                       // CRC wrong
      {cut, 0x800C},                                           // shorter than its length field
  };
  for (std::size_t i = 0; i < cases.size(); ++i) {
    Bench b(ds1000a_strict());
    to_boot(b);
    ASSERT_EQ(foe_reply(b.exchange(kFoE, foe(kWrq, 0, text(kName)))).op, kAck);
    const FoeReply r = send_file(b, cases[i].file);
    EXPECT_EQ(r.op, kErr) << i;
    EXPECT_EQ(r.field, cases[i].code) << i;
    b.request_state(ecat::AlState::Init);
    EXPECT_EQ(version_object(b), "V1.00/1.00") << i;
  }
}

// The download runs in the firmware's interrupt path: no allocation there (docs/architecture.md).
TEST(FoeDownload, DownloadAllocatesNothing) {
  Bench b(ds1000a());
  to_boot(b);
  const std::uint16_t rx = *b.product.mailbox.boot_rx_offset, rx_size = *b.product.mailbox.boot_rx_size;
  const std::uint16_t tx = *b.product.mailbox.boot_tx_offset, tx_size = *b.product.mailbox.boot_tx_size;
  const std::vector<std::uint8_t> file = image("DS1000A-EC", "V1.40/1.00", 1000);  // 1048 bytes: 10 packets
  // Frames built beforehand; the count covers the ESC, the mailbox, the FoE server and its store.
  std::vector<std::vector<std::uint8_t>> writes, reads;
  auto add = [&](const std::vector<std::uint8_t>& payload) {
    std::vector<std::uint8_t> window(rx_size, 0);
    const auto m = message(kFoE, static_cast<std::uint8_t>(writes.size() % 7 + 1), payload);
    std::copy(m.begin(), m.end(), window.begin());
    writes.push_back(Bench::pdu(0x02, rx, window));
    reads.push_back(Bench::pdu(0x01, tx, std::vector<std::uint8_t>(tx_size, 0)));
  };
  add(foe(kWrq, 0, text(kName)));
  for (std::size_t at = 0, packet = 1; at <= file.size(); at += 116, ++packet) {
    const auto from = file.begin() + static_cast<std::ptrdiff_t>(at);
    const auto to = file.begin() + static_cast<std::ptrdiff_t>(std::min(file.size(), at + 116));
    add(foe(kData, static_cast<std::uint32_t>(packet), {from, to}));
  }
  const long before = vdrive::test::allocation_count();
  for (std::size_t i = 0; i < writes.size(); ++i) {
    b.run(writes[i]);
    b.run(reads[i]);
  }
  EXPECT_EQ(vdrive::test::allocation_count() - before, 0);
  // And it was a real download: the last reply is ACK 10 (read frame: 2-byte frame header,
  // 10-byte datagram header, 6-byte mailbox header, then op code and packet number).
  const std::vector<std::uint8_t>& last = reads.back();
  EXPECT_EQ(last[last.size() - 2], 1) << "working counter";
  EXPECT_EQ(last[12 + 6], kAck);
  EXPECT_EQ(last[12 + 6 + 2], 10);
  b.request_state(ecat::AlState::Init);
  EXPECT_EQ(version_object(b), "V1.40/1.00");
}

TEST(FoeDownload, ReadRequestIsNotFound) {
  Bench b(ds1000a());
  to_boot(b);
  const FoeReply r = foe_reply(b.exchange(kFoE, foe(kRrq, 0, text(kName))));
  EXPECT_EQ(r.op, kErr);
  EXPECT_EQ(r.field, 0x8001u) << "download only (L748)";
}

TEST(FoeDownload, ShortRequestIsAMailboxErrorAndCoeIsNotServedInBoot) {
  Bench b(ds1000a());
  to_boot(b);
  auto r = b.exchange(kFoE, {kWrq, 0, 0});
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->at(5) & 0x0F, 0);
  EXPECT_EQ(u16_at(*r, 8), 0x0006) << "size too short";
  r = b.exchange(kCoE, sdo_payload(0x40, 0x1018, 0x01));
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->at(5) & 0x0F, 0);
  EXPECT_EQ(u16_at(*r, 8), 0x0002) << "only FoE in Boot";
}

TEST(FoeDownload, ProductsWithoutFoeAnswerUnsupportedProtocol) {
  // A6B: FoE "×" (L656) and unsupported (L705), though SII word 1Ch = 000Ch has the FoE bit
  // (L3827-L3831); Boot is legal. DS5C1: mailbox type 04h FoE "未对应" (L2512), no Boot (L7115).
  for (const char* id : {"a6b", "ds5c1"}) {
    SCOPED_TRACE(id);
    Bench b(profile::load_profile(id));
    b.to_preop();
    auto r = b.exchange(kFoE, foe(kWrq, 0, text(kName)));
    ASSERT_TRUE(r.has_value());
    EXPECT_EQ(r->at(5) & 0x0F, 0) << "mailbox error reply";
    EXPECT_EQ(u16_at(*r, 8), 0x0002) << "unsupported protocol";
  }
  Bench a6b(profile::load_profile("a6b"));
  to_boot(a6b);
  auto r = a6b.exchange(kFoE, foe(kWrq, 0, text(kName)));
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->at(5) & 0x0F, 0);
  EXPECT_EQ(u16_at(*r, 8), 0x0002) << "A6B Boot: no FoE either";
}

}  // namespace
}  // namespace vdrive::firmware::mailbox_test
