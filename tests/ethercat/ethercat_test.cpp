// The EtherCAT vocabulary against byte patterns from ETG.1000 and the ESC datasheets, and
// round-trips of every typed layout.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <vector>

#include "ethercat/al_state.hpp"
#include "ethercat/al_status_code.hpp"
#include "ethercat/coe.hpp"
#include "ethercat/emergency.hpp"
#include "ethercat/foe.hpp"
#include "ethercat/little_endian.hpp"
#include "ethercat/mailbox_header.hpp"
#include "ethercat/pdo_mapping_entry.hpp"
#include "ethercat/registers.hpp"

namespace vdrive::ecat {
namespace {

// The helpers are meant for constant expressions too (tables, static_asserts).
constexpr std::array<std::uint8_t, 8> kBytes{0x01, 0x23, 0x45, 0x67, 0x89, 0xAB, 0xCD, 0xEF};
static_assert(get_le16(kBytes.data()) == 0x2301);
static_assert(get_le32(kBytes.data()) == 0x67452301u);
static_assert(get_le64(kBytes.data()) == 0xEFCDAB8967452301ull);
static_assert(get_le16(kBytes, 6) == 0xEFCD);
static_assert(get_le(kBytes.data(), 3) == 0x452301u);

TEST(LittleEndian, LoadsLeastSignificantByteFirst) {
  const std::vector<std::uint8_t> b(kBytes.begin(), kBytes.end());
  EXPECT_EQ(get_le16(b, 1), 0x4523);
  EXPECT_EQ(get_le32(b, 4), 0xEFCDAB89u);
  EXPECT_EQ(get_le64(b, 0), 0xEFCDAB8967452301ull);
  EXPECT_EQ(get_le(std::span<const std::uint8_t>(b).first(2)), 0x2301u);
  EXPECT_EQ(get_le(std::span<const std::uint8_t>()), 0u);
  const std::vector<std::uint8_t> wide(12, 0xFF);
  EXPECT_EQ(get_le(wide), ~std::uint64_t{0}) << "at most 8 bytes count";
}

TEST(LittleEndian, StoresRoundTrip) {
  std::array<std::uint8_t, 10> b{};
  put_le16(b, 0, 0xBEEF);
  EXPECT_EQ(b[0], 0xEF);
  EXPECT_EQ(b[1], 0xBE);
  put_le32(b.data() + 2, 0x12345678u);
  EXPECT_EQ((std::array<std::uint8_t, 4>{b[2], b[3], b[4], b[5]}), (std::array<std::uint8_t, 4>{0x78, 0x56, 0x34, 0x12}));
  EXPECT_EQ(get_le32(b, 2), 0x12345678u);
  put_le64(b, 2, 0x0102030405060708ull);
  EXPECT_EQ(get_le64(b.data() + 2), 0x0102030405060708ull);
  EXPECT_EQ(b[2], 0x08);
  EXPECT_EQ(b[9], 0x01);
  put_le(b.data(), 0xAABBCC, 3);
  EXPECT_EQ(get_le(b.data(), 3), 0xAABBCCu);
  EXPECT_EQ(b[3], 0x07) << "bytes past the field are left alone";
}

TEST(LittleEndian, WideFieldsAreZeroExtended) {
  std::array<std::uint8_t, 10> b;
  b.fill(0x55);
  put_le(b, 0x1122334455667788ull);
  EXPECT_EQ(get_le64(b, 0), 0x1122334455667788ull);
  EXPECT_EQ(b[8], 0);
  EXPECT_EQ(b[9], 0);
  b.fill(0x55);
  put_le(b.data(), 0x11, 10);
  EXPECT_EQ(b[0], 0x11);
  EXPECT_EQ(b[9], 0);
}

TEST(Registers, DcMapIsTheEt1100Map) {
  EXPECT_EQ(reg::kDcSystemTime, 0x0910);
  EXPECT_EQ(reg::kDcSystemTimeOffset, 0x0920);
  EXPECT_EQ(reg::kDcSystemTimeDelay, 0x0928);
  EXPECT_EQ(reg::kDcSpeedCounterStart, 0x0930);
  EXPECT_EQ(reg::kDcCyclicUnitControl, 0x0980);
  EXPECT_EQ(reg::kDcActivation, 0x0981);
  EXPECT_EQ(reg::kDcActivationStatus, 0x0984);
  EXPECT_EQ(reg::kDcStartTime, 0x0990);
  EXPECT_EQ(reg::kDcNextSync1, 0x0998);
  EXPECT_EQ(reg::kDcSync0CycleTime, 0x09A0);
  EXPECT_EQ(reg::kDcSync1CycleTime, 0x09A4);
  // SOEM's ecx_dcsync0 writes 0x03 to 0x0981 (cyclic unit + SYNC0).
  EXPECT_EQ(reg::dc_activation::kCyclicOperation | reg::dc_activation::kSync0, 0x03);
  EXPECT_LT(reg::kDcLatch1Control, reg::kDcEnd);
}

TEST(AlState, ControlAndStatusBits) {
  // AL Control 0x0012: Pre-Op requested with the error acknowledged.
  const AlControl c = AlControl::decode(0x0012);
  EXPECT_EQ(c.requested, 0x2);
  EXPECT_TRUE(c.error_ack);
  EXPECT_FALSE(c.id_request);
  EXPECT_EQ(AlStatusBits::encode(AlState::SafeOp, true, false), 0x0014);  // Safe-Op + error
  EXPECT_EQ(AlStatusBits::encode(AlState::Op, false, true), 0x0028);
  EXPECT_TRUE(is_defined_state(0x8));
  EXPECT_FALSE(is_defined_state(0x5));
  EXPECT_LT(rank(AlState::PreOp), rank(AlState::SafeOp));
  EXPECT_EQ(rank(AlState::Boot), rank(AlState::PreOp));
  EXPECT_EQ(name(AlState::SafeOp), "SafeOp");
}

TEST(AlStatusCode, EtgValuesAndNames) {
  EXPECT_EQ(al_status_code::kInvalidStateChange, 0x0011);
  EXPECT_EQ(al_status_code::kSyncManagerWatchdog, 0x001B);
  EXPECT_EQ(al_status_code::kEepromError, 0x0051);
  EXPECT_EQ(al_status_code::name(0x001B), "Sync manager watchdog");
  EXPECT_EQ(al_status_code::name(0x8123), "Vendor specific");
  EXPECT_EQ(al_status_code::name(0x00EE), "Unknown AL status code");
}

TEST(MailboxHeader, DecodesTheWireBytes) {
  // A CoE request of 10 bytes from the master (address 0), priority 0, counter 1.
  const std::array<std::uint8_t, 6> wire{0x0A, 0x00, 0x00, 0x00, 0x00, 0x13};
  const mailbox::Header h = mailbox::Header::decode(wire);
  EXPECT_EQ(h.length, 10);
  EXPECT_EQ(h.address, 0);
  EXPECT_EQ(h.type, static_cast<std::uint8_t>(mailbox::Type::CoE));
  EXPECT_EQ(h.counter, 1);
  std::array<std::uint8_t, 6> out{};
  h.encode(out);
  EXPECT_EQ(out, wire);
}

TEST(MailboxHeader, RoundTripsEveryField) {
  const mailbox::Header h{0x0123, 0x1001, 0x2A, 3, static_cast<std::uint8_t>(mailbox::Type::FoE), 7};
  std::array<std::uint8_t, mailbox::kHeaderSize> b{};
  h.encode(b);
  EXPECT_EQ(b[4], 0x2A | (3 << 6));
  EXPECT_EQ(b[5], 0x74);
  EXPECT_EQ(mailbox::Header::decode(b), h);
  EXPECT_EQ(mailbox::next_counter(7), 1);
  EXPECT_EQ(mailbox::next_counter(0), 1);
}

TEST(MailboxHeader, ErrorPayload) {
  std::array<std::uint8_t, mailbox::kErrorPayloadSize> b{};
  mailbox::encode_error_payload(b, mailbox::ErrorCode::InvalidSize);
  EXPECT_EQ(b, (std::array<std::uint8_t, 4>{0x01, 0x00, 0x08, 0x00}));
}

TEST(Coe, HeaderAndSdoCommand) {
  std::array<std::uint8_t, coe::sdo::kInitiateSize> b{};
  coe::put_coe_header(b, coe::Service::SdoRequest);
  EXPECT_EQ(b[0], 0x00);
  EXPECT_EQ(b[1], 0x20);  // service 2 in bits 15:12
  EXPECT_EQ(coe::service_of(b), coe::Service::SdoRequest);
  // Expedited download of 4 bytes (ETG.1000.6: 0x23) is ccs 1; an upload request (0x40) ccs 2.
  EXPECT_EQ(coe::sdo::ccs_of(0x23), coe::sdo::Ccs::InitiateDownload);
  EXPECT_EQ(coe::sdo::ccs_of(0x40), coe::sdo::Ccs::InitiateUpload);
  EXPECT_EQ(coe::sdo::ccs_of(coe::sdo::kAbort), coe::sdo::Ccs::Abort);
}

TEST(Coe, EmergencyLayout) {
  coe::Emergency e;
  e.error_code = 0xFF10;
  e.error_register = 0x80;
  e.data = {0x07, 0, 0, 0, 0x42};
  std::array<std::uint8_t, coe::Emergency::kPayloadSize> b{};
  e.encode(b);
  EXPECT_EQ(b, (std::array<std::uint8_t, 10>{0x00, 0x10, 0x10, 0xFF, 0x80, 0x07, 0, 0, 0, 0x42}));
  EXPECT_EQ(coe::Emergency::decode(b), e);
}

TEST(Foe, HeaderLayout) {
  std::array<std::uint8_t, foe::kHeaderSize> b{};
  foe::put_header(b, foe::OpCode::Ack, 5);
  EXPECT_EQ(b, (std::array<std::uint8_t, 6>{0x04, 0x00, 0x05, 0x00, 0x00, 0x00}));
  EXPECT_EQ(foe::opcode_of(b), foe::OpCode::Ack);
  EXPECT_EQ(foe::field_of(b), 5u);
  EXPECT_EQ(foe::error_text(foe::ErrorCode::NotFound), "Not found");
}

TEST(PdoMappingEntry, EncodesIndexSubindexBits) {
  const PdoMappingEntry e = PdoMappingEntry::decode(0x607A0020);  // target position, 32 bits
  EXPECT_EQ(e.index, 0x607A);
  EXPECT_EQ(e.subindex, 0);
  EXPECT_EQ(e.bits, 32);
  EXPECT_EQ(e.encode(), 0x607A0020u);
  EXPECT_EQ(PdoMappingEntry::decode(PdoMappingEntry::encode(0x6041, 0, 16)), (PdoMappingEntry{0x6041, 0, 16}));
  EXPECT_TRUE(PdoMappingEntry::decode(0x00050008).is_gap()) << "a dummy entry (UNSIGNED8)";
  EXPECT_FALSE(e.is_gap());
}

}  // namespace
}  // namespace vdrive::ecat
