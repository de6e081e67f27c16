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


// ---- DS5C1 digit-field parameters and undocumented indexes (issue 22 item 8) ------------------

class Ds5c1Store : public ::testing::Test {
protected:
  static void SetUpTestSuite() { dict_ = new Dictionary(Dictionary::load(profile::load_profile("ds5c1"))); }
  static void TearDownTestSuite() { delete dict_; }
  static Dictionary* dict_;
  ObjectStore store_{*dict_};
  SdoAbort write16(std::uint16_t index, std::uint16_t value) {
    return store_.write(index, 0, le<std::uint16_t>(value), AlState::PreOp);
  }
};
Dictionary* Ds5c1Store::dict_ = nullptr;

// App. 1.1 gives hexadecimal parameters a range per digit (P0-09.0 0~1, .2 0~F, .3 0~7, L8659-L8665):
// a field outside its range aborts as a whole value would, 06090031h above, 06090032h below.
TEST_F(Ds5c1Store, AHexDigitFieldOutsideItsRangeAborts) {
  EXPECT_EQ(write16(0x2009, 0x7F01), SdoAbort::Ok);            // every field at its maximum
  EXPECT_EQ(write16(0x2009, 0x0002), SdoAbort::ValueTooHigh);  // P0-09.0 = 2 > 1
  EXPECT_EQ(write16(0x2009, 0x8000), SdoAbort::ValueTooHigh);  // P0-09.3 = 8 > 7
  EXPECT_EQ(write16(0x2009, 0x00F0), SdoAbort::Ok);            // digit 1: no field, any value (L8659-L8665 skip it)
  EXPECT_EQ(write16(0x2202, 0x0303), SdoAbort::Ok);            // P2-02.0 / .2 1~3 (L8737-L8738)
  EXPECT_EQ(write16(0x2202, 0x0300), SdoAbort::ValueTooLow);   // P2-02.0 = 0 < 1
  EXPECT_EQ(write16(0x2701, 0x2216), SdoAbort::Ok);            // P7-01.0~1 00..16 listed (L8954-L8958)
  EXPECT_EQ(write16(0x2701, 0x2217), SdoAbort::ValueTooHigh);
  EXPECT_EQ(write16(0x2044, 0x0000), SdoAbort::ValueTooLow);   // P0-68.0~1 0x01~0xFF (L8687)
}

// P5-21, P5-26 and P5-61 (L8868-L8869, L8878, L8923): fields 0~ff and 0~f cover whole digits, so
// every value their digits can hold is taken; digit 3 (and 2-3 of P5-61) is documented by no field
// and takes any value, no stricter than the manual.
TEST_F(Ds5c1Store, TheP5TerminalParametersTakeWhatTheirDigitsHold) {
  for (const std::uint16_t index : {0x2515, 0x251A, 0x253D}) {
    const EntryDesc* e = dict_->find(index, 0);
    ASSERT_NE(e, nullptr);
    ASSERT_FALSE(e->digit_fields.empty()) << std::hex << index;
    EXPECT_EQ(e->digit_fields[0].max, 0xFF) << std::hex << index;
    EXPECT_EQ(write16(index, 0x0014), SdoAbort::Ok) << std::hex << index;   // SI4 inverse (L8866)
    EXPECT_EQ(write16(index, 0xFFFF), SdoAbort::Ok) << std::hex << index;
  }
  EXPECT_EQ(dict_->find(0x2515, 0)->digit_fields.size(), 2u);   // .0~1 and .2
  EXPECT_EQ(dict_->find(0x253D, 0)->digit_fields.size(), 1u);   // .0~1 only
}

// The 253 indexes App. 2.2 declares and App. 1.1 does not document (P0-06, ...) are 16-bit registers
// with no range: any 16-bit value is stored and read back; a write of another length is refused.
TEST_F(Ds5c1Store, UndocumentedIndexesTakeAny16BitValue) {
  std::size_t undocumented = 0;
  for (const ObjectDesc& o : dict_->objects())
    if (o.index >= 0x2000 && o.index < 0x3000 && !o.entries[0].min && !o.entries[0].max &&
        o.entries[0].digit_fields.empty())
      ++undocumented;
  EXPECT_EQ(undocumented, 253u + 7u);   // + P4-10/P4-11, P5-57..59, P5-62/63: documented, range not a number
  EXPECT_EQ(write16(0x2006, 0xFFFF), SdoAbort::Ok);   // P0-06
  EXPECT_EQ(read_unsigned(store_, 0x2006, 0), 0xFFFFu);
  EXPECT_EQ(store_.write(0x2006, 0, le<std::uint32_t>(1), AlState::PreOp), SdoAbort::LengthMismatch);
}

// ---- DS5C1 chapter 8.3 objects (issue 22 item 7) ----------------------------------------------

// 8.3.1 (L5785-L5832) lists 3000h-3061h (U0-00..U0-97), 3100h/3101h (U1-00/01), 4000h (F0-00),
// 4106h (F1-06) and the typed 5000h-5002h, although App. 2 calls 3000h-5FFFh reserved (L9165-L9167).
TEST_F(Ds5c1Store, Chapter8ObjectsOf3000hTo5FFFhArePresent) {
  for (std::uint16_t i = 0x3000; i <= 0x3061; ++i) {
    const EntryDesc* e = dict_->find(i, 0);
    ASSERT_NE(e, nullptr) << std::hex << i;
    EXPECT_EQ(e->access & access::kWriteAll, 0) << "a monitor is read-only";
  }
  EXPECT_EQ(dict_->find(0x3062, 0), nullptr);
  for (const std::uint16_t i : {0x3100, 0x3101}) EXPECT_NE(dict_->find(i, 0), nullptr);
  EXPECT_EQ(write16(0x4000, 1), SdoAbort::Ok);   // F0-00 alarm clear (L7408-L7412)
  EXPECT_EQ(write16(0x4106, 1), SdoAbort::Ok);   // F1-06 multi-turn clear (L1901, L2056)
  const EntryDesc* pos = dict_->find(0x5000, 0);
  ASSERT_NE(pos, nullptr);
  EXPECT_EQ(pos->type, DataType::Integer32);     // L5830
  EXPECT_NE(pos->access & access::kTxPdoMappable, 0);
  const EntryDesc* decel = dict_->find(0x5002, 0);
  ASSERT_NE(decel, nullptr);
  EXPECT_EQ(decel->type, DataType::Unsigned16);  // L5832
  EXPECT_NE(decel->access & access::kRxPdoMappable, 0);
  EXPECT_EQ(store_.write(0x5000, 0, le<std::int32_t>(0), AlState::PreOp), SdoAbort::ReadOnly);
}

// ---- DS1000A-EC objects documented outside 13.2.1 (issue 22 items 5 and 6) -------------------

class Ds1000aStore : public ::testing::Test {
protected:
  static void SetUpTestSuite() { dict_ = new Dictionary(Dictionary::load(profile::load_profile("ds1000a"))); }
  static void TearDownTestSuite() { delete dict_; }
  static Dictionary* dict_;
  ObjectStore store_{*dict_};
};
Dictionary* Ds1000aStore::dict_ = nullptr;

// 60D9h/60DAh "Supported: Yes" in 13.2.2 (L5429, L5431); 2156h/2157h in the 11.1.2 prose (L4198, L4210).
TEST_F(Ds1000aStore, ObjectsDocumentedOutsideTheTableArePresent) {
  EXPECT_EQ(read_unsigned(store_, 0x60D9, 0), 0u);   // no ETG.6010 synchronisation function
  EXPECT_EQ(store_.write(0x60D9, 0, le<std::uint32_t>(1), AlState::PreOp), SdoAbort::ReadOnly);
  EXPECT_EQ(store_.write(0x60DA, 0, le<std::uint32_t>(0x12345678), AlState::PreOp), SdoAbort::Ok);
  EXPECT_EQ(read_unsigned(store_, 0x60DA, 0), 0x12345678u);
  EXPECT_EQ(store_.write(0x2156, 0, le<std::uint8_t>(2), AlState::PreOp), SdoAbort::Ok);    // 2: command torque
  EXPECT_EQ(store_.write(0x2156, 0, le<std::uint8_t>(3), AlState::PreOp), SdoAbort::ValueTooHigh);
  EXPECT_EQ(store_.write(0x2157, 0, le<std::uint8_t>(3), AlState::PreOp), SdoAbort::Ok);    // 3: in-position
}

// 11.1 and 13.2.1 disagree (L3905-L3979 / L4806-L4868); the dictionary keeps 13.2.1's type, which sets
// the SDO length a master sends: 1 byte for 210Dh, 2119h, 211Ch, 2154h, 2158h-215Fh, 2162h, 2163h
// (11.1: U16), and for 210Fh/2117h (11.1: BOOL, also 1 byte); 2 bytes for 2143h (11.1: BOOL);
// 210Eh 0-5000 (11.1: 0-3000) and 210Fh 0-2 (11.1 and the prose L4060-L4065: 0-1), the wider ranges.
TEST_F(Ds1000aStore, ConflictingTypesFollow13_2_1) {
  for (const std::uint16_t i : {0x210D, 0x2119, 0x211C, 0x2154, 0x2158, 0x2159, 0x215A, 0x215B, 0x215C, 0x215D,
                                0x215E, 0x215F, 0x2162, 0x2163, 0x210F, 0x2117}) {
    EXPECT_EQ(dict_->find(i, 0)->type, DataType::Unsigned8) << std::hex << i;
    EXPECT_EQ(store_.write(i, 0, le<std::uint16_t>(0), AlState::PreOp), SdoAbort::LengthMismatch) << std::hex << i;
  }
  EXPECT_EQ(dict_->find(0x2143, 0)->type, DataType::Unsigned16);
  EXPECT_EQ(dict_->find(0x2108, 0)->type, DataType::Integer32);
  EXPECT_EQ(store_.write(0x210E, 0, le<std::uint16_t>(5000), AlState::PreOp), SdoAbort::Ok);
  EXPECT_EQ(store_.write(0x210F, 0, le<std::uint8_t>(2), AlState::PreOp), SdoAbort::Ok);
}

}  // namespace
}  // namespace vdrive::od
