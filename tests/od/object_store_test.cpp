// ObjectStore: CoE SDO access rules on real dictionaries (A6B, DS1000A-EC) and a hand-written one:
// abort codes for missing objects/subindexes, read-only, state, length and range; write hooks;
// strings; defaults after reset; and no allocation on read/write.
#include <gtest/gtest.h>

#include <array>

#include "tests/od/od_test_support.hpp"
#include "vdrive/od/dictionary.hpp"
#include "vdrive/od/object_store.hpp"
#include "vdrive/od/objects_yaml.hpp"
#include "vdrive/profile/profile_loader.hpp"
#include "tests/support/allocation_counter.hpp"


namespace vdrive::od {
namespace {

using namespace od::test;
using ecat::AlState;

class A6bStore : public ::testing::Test {
protected:
  static void SetUpTestSuite() { dict_ = new Dictionary(Dictionary::load(profile::load_profile("a6b"))); }
  static void TearDownTestSuite() { delete dict_; }
  static Dictionary* dict_;
  ObjectStore store_{*dict_};
  std::array<std::uint8_t, 64> buf_{};
  std::size_t n_ = 0;
};
Dictionary* A6bStore::dict_ = nullptr;

TEST_F(A6bStore, MissingObjectAndSubindexAbort) {
  EXPECT_EQ(store_.read(0x7777, 0, buf_, n_, AlState::PreOp), SdoAbort::NoSuchObject);
  EXPECT_EQ(static_cast<std::uint32_t>(SdoAbort::NoSuchObject), 0x06020000u);
  EXPECT_EQ(store_.read(0x6040, 1, buf_, n_, AlState::PreOp), SdoAbort::NoSuchSubindex);
  EXPECT_EQ(static_cast<std::uint32_t>(SdoAbort::NoSuchSubindex), 0x06090011u);
  EXPECT_EQ(store_.write(0x7777, 0, le<std::uint16_t>(1), AlState::PreOp), SdoAbort::NoSuchObject);
  EXPECT_EQ(store_.write(0x1018, 9, le<std::uint32_t>(1), AlState::PreOp), SdoAbort::NoSuchSubindex);
  EXPECT_EQ(n_, 0u);
}

TEST_F(A6bStore, ReadOnlyEntriesRefuseWrites) {
  EXPECT_EQ(store_.write(0x6041, 0, le<std::uint16_t>(1), AlState::PreOp), SdoAbort::ReadOnly);
  EXPECT_EQ(store_.write(0x1018, 1, le<std::uint32_t>(1), AlState::Op), SdoAbort::ReadOnly);
  EXPECT_EQ(store_.write(0x6082, 0, le<std::uint32_t>(1), AlState::PreOp), SdoAbort::ReadOnly);  // attribute X
  EXPECT_EQ(static_cast<std::uint32_t>(SdoAbort::ReadOnly), 0x06010002u);
  EXPECT_EQ(read_unsigned(store_, 0x1018, 1), 0x0000066Fu);
}

TEST_F(A6bStore, PdoAssignmentIsWritableInPreOpOnly) {
  // A6B answers 06010003h outside PreOp (L4411-L4552 abort table, L6902).
  EXPECT_EQ(store_.write(0x1C12, 1, le<std::uint16_t>(0x1601), AlState::PreOp), SdoAbort::Ok);
  EXPECT_EQ(read_unsigned(store_, 0x1C12, 1), 0x1601u);
  EXPECT_EQ(store_.write(0x1C12, 1, le<std::uint16_t>(0x1602), AlState::SafeOp), SdoAbort::SubindexCannotBeWritten);
  EXPECT_EQ(store_.write(0x1C12, 1, le<std::uint16_t>(0x1602), AlState::Op), SdoAbort::SubindexCannotBeWritten);
  EXPECT_EQ(static_cast<std::uint32_t>(SdoAbort::SubindexCannotBeWritten), 0x06010003u);
  EXPECT_EQ(read_unsigned(store_, 0x1C12, 1), 0x1601u);
  // Other rw objects are writable in every state with a mailbox.
  for (AlState s : {AlState::PreOp, AlState::SafeOp, AlState::Op})
    EXPECT_EQ(store_.write(0x6040, 0, le<std::uint16_t>(6), s), SdoAbort::Ok);
}

TEST_F(A6bStore, BootHasNoCoe) {
  EXPECT_EQ(store_.read(0x6040, 0, buf_, n_, AlState::Boot), SdoAbort::WrongState);
  EXPECT_EQ(store_.write(0x6040, 0, le<std::uint16_t>(6), AlState::Boot), SdoAbort::WrongState);
  EXPECT_EQ(static_cast<std::uint32_t>(SdoAbort::WrongState), 0x08000022u);
}

TEST_F(A6bStore, LengthMustMatchTheType) {
  // A6B: 06070012h/06070013h are "not supported"; every length error is 06070010h.
  EXPECT_EQ(store_.write(0x6040, 0, le<std::uint8_t>(6), AlState::PreOp), SdoAbort::LengthMismatch);
  EXPECT_EQ(store_.write(0x6040, 0, le<std::uint32_t>(6), AlState::PreOp), SdoAbort::LengthMismatch);
  EXPECT_EQ(store_.write(0x6040, 0, {}, AlState::PreOp), SdoAbort::LengthMismatch);
  EXPECT_EQ(static_cast<std::uint32_t>(SdoAbort::LengthMismatch), 0x06070010u);
  EXPECT_EQ(read_unsigned(store_, 0x6040, 0), 0u);
}

TEST_F(A6bStore, ValuesOutsideTheRangeAbort) {
  // 1C12h:01 ranges 1600h-1603h.
  EXPECT_EQ(store_.write(0x1C12, 1, le<std::uint16_t>(0x1604), AlState::PreOp), SdoAbort::ValueTooHigh);
  EXPECT_EQ(store_.write(0x1C12, 1, le<std::uint16_t>(0x15FF), AlState::PreOp), SdoAbort::ValueTooLow);
  EXPECT_EQ(static_cast<std::uint32_t>(SdoAbort::ValueTooHigh), 0x06090031u);
  EXPECT_EQ(static_cast<std::uint32_t>(SdoAbort::ValueTooLow), 0x06090032u);
  // 1C12h:00 ranges 0..4.
  EXPECT_EQ(store_.write(0x1C12, 0, le<std::uint8_t>(5), AlState::PreOp), SdoAbort::ValueTooHigh);
  EXPECT_EQ(store_.write(0x1C12, 0, le<std::uint8_t>(4), AlState::PreOp), SdoAbort::Ok);
}

TEST_F(A6bStore, SignedValuesAreComparedAsSigned) {
  // 6060h I8 -128..127: 0xFF is -1, in range.
  EXPECT_EQ(store_.write(0x6060, 0, le<std::int8_t>(-1), AlState::Op), SdoAbort::Ok);
  EXPECT_EQ(read_bytes(store_, 0x6060, 0), (std::vector<std::uint8_t>{0xFF}));
}

TEST_F(A6bStore, ReadsIntoTooSmallABufferAbort) {
  std::array<std::uint8_t, 2> small{};
  EXPECT_EQ(store_.read(0x1018, 1, small, n_, AlState::PreOp), SdoAbort::ObjectTooLong);
  EXPECT_EQ(n_, 0u);
}

TEST_F(A6bStore, HooksSeeTheWriteAndMayRefuseIt) {
  std::vector<std::string> calls;
  store_.on_write(0x6040, [&](const EntryDesc& e, std::span<const std::uint8_t> data) {
    calls.push_back("first " + std::to_string(e.index) + " " + std::to_string(data[0]));
    return SdoAbort::Ok;
  });
  store_.on_write(0x6040, [&](const EntryDesc&, std::span<const std::uint8_t> data) {
    calls.push_back("second");
    return data[0] == 0x80 ? SdoAbort::WrongState : SdoAbort::Ok;
  });
  store_.on_write(0x6060, [&](const EntryDesc&, std::span<const std::uint8_t>) {
    calls.push_back("6060");
    return SdoAbort::Ok;
  });

  EXPECT_EQ(store_.write(0x6040, 0, le<std::uint16_t>(0x0F), AlState::Op), SdoAbort::Ok);
  EXPECT_EQ(calls, (std::vector<std::string>{"first 24640 15", "second"}));
  EXPECT_EQ(read_unsigned(store_, 0x6040, 0), 0x0Fu);

  calls.clear();
  EXPECT_EQ(store_.write(0x6040, 0, le<std::uint16_t>(0x80), AlState::Op), SdoAbort::WrongState);
  EXPECT_EQ(read_unsigned(store_, 0x6040, 0), 0x0Fu);   // refused: not stored

  // A write that fails the store's own checks never reaches the hooks.
  calls.clear();
  EXPECT_EQ(store_.write(0x6040, 0, le<std::uint8_t>(1), AlState::Op), SdoAbort::LengthMismatch);
  EXPECT_TRUE(calls.empty());
}

TEST_F(A6bStore, FirmwareWritesThroughRawAndResetRestoresDefaults) {
  const EntryDesc* statusword = dict_->find(0x6041, 0);
  store_.raw(*statusword)[0] = 0x37;
  EXPECT_EQ(read_unsigned(store_, 0x6041, 0), 0x37u);
  ASSERT_EQ(store_.write(0x1C12, 1, le<std::uint16_t>(0x1603), AlState::PreOp), SdoAbort::Ok);
  store_.reset_to_defaults();
  EXPECT_EQ(read_unsigned(store_, 0x6041, 0), 0u);
  EXPECT_EQ(read_unsigned(store_, 0x1C12, 1), 0x1600u);
  EXPECT_EQ(read_string(store_, 0x1008, 0), "MADLN15BE");
}

TEST_F(A6bStore, ReadAndWriteAllocateNothing) {
  store_.on_write(0x6040, [](const EntryDesc&, std::span<const std::uint8_t>) { return SdoAbort::Ok; });
  const auto value = le<std::uint16_t>(0x0F);
  const auto too_long = le<std::uint32_t>(1);
  const long before = vdrive::test::allocation_count();
  for (int i = 0; i < 100; ++i) {
    EXPECT_EQ(store_.write(0x6040, 0, value, AlState::Op), SdoAbort::Ok);
    EXPECT_EQ(store_.write(0x6040, 0, too_long, AlState::Op), SdoAbort::LengthMismatch);
    EXPECT_EQ(store_.write(0x1C12, 1, value, AlState::Op), SdoAbort::SubindexCannotBeWritten);
    EXPECT_EQ(store_.read(0x6041, 0, buf_, n_, AlState::Op), SdoAbort::Ok);
    EXPECT_EQ(store_.read(0x1008, 0, buf_, n_, AlState::Op), SdoAbort::Ok);
    EXPECT_EQ(store_.read(0x7777, 0, buf_, n_, AlState::Op), SdoAbort::NoSuchObject);
  }
  store_.reset_to_defaults();
  EXPECT_EQ(vdrive::test::allocation_count(), before);
}

// ---- strings and BOOL, hand-written --------------------------------------------------------

const char* kStrings =
    "  - {index: 0x2100, name: \"Label\", object_code: VAR, line: 1, entries: [\n"
    "      {subindex: 0x00, name: \"Label\", data_type: VS, access: rw, pdo: \"no\", default: \"abcdef\", min: null, max: null, units: null, line: 1}]}\n"
    "  - {index: 0x2101, name: \"Blob\", object_code: VAR, line: 2, entries: [\n"
    "      {subindex: 0x00, name: \"Blob\", data_type: OS, access: rw, pdo: \"no\", default: null, min: null, max: null, units: null, line: 2}]}\n"
    "  - {index: 0x2102, name: \"Flag\", object_code: VAR, line: 3, entries: [\n"
    "      {subindex: 0x00, name: \"Flag\", data_type: BOOL, access: rw, pdo: rx, default: 1, min: null, max: null, units: null, line: 3}]}\n";

class HandWrittenStore : public ::testing::Test {
protected:
  HandWrittenStore() : dir_("odtest", yaml_header("odtest", 3, 3) + kStrings), dict_(Dictionary::load(test_product(), dir_.path())) {}
  TempObjectsDir dir_;
  Dictionary dict_;
  ObjectStore store_{dict_};
};

TEST_F(HandWrittenStore, AVisibleStringReadsAsLongAsWhatIsStored) {
  EXPECT_EQ(dict_.find(0x2100, 0)->bit_length, 48);   // capacity = the default's length
  EXPECT_EQ(read_string(store_, 0x2100, 0), "abcdef");
  const std::string shorter = "xy";
  EXPECT_EQ(store_.write(0x2100, 0, std::span(reinterpret_cast<const std::uint8_t*>(shorter.data()), shorter.size()),
                         AlState::PreOp),
            SdoAbort::Ok);
  EXPECT_EQ(read_string(store_, 0x2100, 0), "xy");
  const std::string longer = "abcdefg";
  EXPECT_EQ(store_.write(0x2100, 0, std::span(reinterpret_cast<const std::uint8_t*>(longer.data()), longer.size()),
                         AlState::PreOp),
            SdoAbort::LengthMismatch);
  EXPECT_EQ(read_string(store_, 0x2100, 0), "xy");
}

TEST_F(HandWrittenStore, AnOctetStringReadsItsWholeCapacity) {
  EXPECT_EQ(read_bytes(store_, 0x2101, 0), std::vector<std::uint8_t>(kDefaultStringBytes, 0));
  const std::vector<std::uint8_t> data = {0, 1, 0, 2};
  ASSERT_EQ(store_.write(0x2101, 0, data, AlState::PreOp), SdoAbort::Ok);
  std::vector<std::uint8_t> expected(kDefaultStringBytes, 0);
  expected[1] = 1;
  expected[3] = 2;
  EXPECT_EQ(read_bytes(store_, 0x2101, 0), expected);
}

TEST_F(HandWrittenStore, ABoolIsOneByteHoldingZeroOrOne) {
  EXPECT_EQ(dict_.find(0x2102, 0)->bit_length, 1);
  EXPECT_EQ(read_bytes(store_, 0x2102, 0), (std::vector<std::uint8_t>{1}));
  EXPECT_EQ(store_.write(0x2102, 0, le<std::uint8_t>(0), AlState::Op), SdoAbort::Ok);
  EXPECT_EQ(store_.write(0x2102, 0, le<std::uint8_t>(2), AlState::Op), SdoAbort::ValueRangeExceeded);
  EXPECT_EQ(read_bytes(store_, 0x2102, 0), (std::vector<std::uint8_t>{0}));
}

}  // namespace
}  // namespace vdrive::od
