// Command-line SDO values: text to little-endian bytes and back, with one-line errors.
#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

#include "master/value_text.hpp"

namespace vdrive::master {
namespace {

using Bytes = std::vector<std::uint8_t>;

TEST(ValueText, IntegersAreLittleEndianOfTheTypesWidth) {
  EXPECT_EQ(encode_value("u16", "0x6040"), (Bytes{0x40, 0x60}));
  EXPECT_EQ(encode_value("u8", "255"), (Bytes{0xFF}));
  EXPECT_EQ(encode_value("u32", "100000"), (Bytes{0xA0, 0x86, 0x01, 0x00}));
  EXPECT_EQ(encode_value("i16", "-2"), (Bytes{0xFE, 0xFF}));
  EXPECT_EQ(encode_value("i8", "-128"), (Bytes{0x80}));
  EXPECT_EQ(encode_value("i64", "-1"), Bytes(8, 0xFF));
}

TEST(ValueText, OutOfRangeAndGarbageAreRefused) {
  EXPECT_THROW(encode_value("u8", "256"), std::invalid_argument);
  EXPECT_THROW(encode_value("i8", "128"), std::invalid_argument);
  EXPECT_THROW(encode_value("i8", "-129"), std::invalid_argument);
  EXPECT_THROW(encode_value("u16", "-1"), std::invalid_argument);
  EXPECT_THROW(encode_value("u16", "12x"), std::invalid_argument);
  EXPECT_THROW(encode_value("u16", ""), std::invalid_argument);
  EXPECT_THROW(encode_value("hex", "123"), std::invalid_argument);
  EXPECT_THROW(encode_value("f32", "1"), std::invalid_argument);
}

TEST(ValueText, StringsAndHex) {
  EXPECT_EQ(encode_value("string", "DS5C1"), (Bytes{'D', 'S', '5', 'C', '1'}));
  EXPECT_EQ(encode_value("hex", "01 0a:FF"), (Bytes{0x01, 0x0A, 0xFF}));
  EXPECT_EQ(decode_value("hex", Bytes{0x01, 0x0A}), "01 0A");
  EXPECT_EQ(decode_value("string", Bytes{'A', '6'}), "A6");
}

TEST(ValueText, DecodeShowsHexAndDecimal) {
  EXPECT_EQ(decode_value("u16", Bytes{0x50, 0x02}), "0x0250 (592)");
  EXPECT_EQ(decode_value("i16", Bytes{0xFE, 0xFF}), "0xFFFE (-2)");
  EXPECT_EQ(decode_value("i32", Bytes{0x10, 0, 0, 0}), "0x00000010 (16)");
  EXPECT_EQ(decode_value("u32", Bytes{0x08}), "0x08 (8)") << "the reply's own length wins";
}

}  // namespace
}  // namespace vdrive::master
