// How people name slaves: positions from 1, station addresses in hex, one label for both.
#include "ethercat/slave_ref.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <string>

namespace vdrive::ecat {
namespace {

using ::testing::HasSubstr;

std::string refusal(std::string_view text) {
  try {
    (void)parse_slave_ref(text);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "accepted";
}

TEST(SlaveRef, APositionCountsFromOneAndAnAddressIsHex) {
  const SlaveRef two = parse_slave_ref("2");
  EXPECT_FALSE(two.is_address());
  EXPECT_EQ(two.value, 2);
  const SlaveRef address = parse_slave_ref("0x1002");
  EXPECT_TRUE(address.is_address());
  EXPECT_EQ(address.value, 0x1002);
  EXPECT_EQ(parse_slave_ref("0X10aB").value, 0x10AB);
}

TEST(SlaveRef, RefusalsSayWhatIsAccepted) {
  EXPECT_THAT(refusal("0"), HasSubstr("positions count from 1"));
  EXPECT_THAT(refusal("0x0000"), HasSubstr("no slave's"));
  EXPECT_THAT(refusal("two"), HasSubstr("'two' names no slave: give a position (1 = first in cable order) or a station address"));
  EXPECT_THAT(refusal(""), HasSubstr("names no slave"));
  EXPECT_THAT(refusal("-1"), HasSubstr("names no slave"));
  EXPECT_THAT(refusal("2x"), HasSubstr("names no slave"));
  EXPECT_THAT(refusal("0x"), HasSubstr("names no slave"));
  EXPECT_THAT(refusal("0x10000"), HasSubstr("names no slave"));
  EXPECT_THAT(refusal("65536"), HasSubstr("names no slave"));
}

TEST(SlaveRef, AProblemIsEmptyForAReference) {
  EXPECT_EQ(slave_ref_problem("0x1001"), "");
  EXPECT_EQ(slave_ref_problem("3"), "");
  EXPECT_THAT(slave_ref_problem("0"), HasSubstr("positions count from 1"));
}

TEST(SlaveRef, FindsTheSlaveByPositionOrAddress) {
  const std::array<std::uint16_t, 3> stations{0x1001, 0x1002, 0x1003};
  EXPECT_EQ(slave_index(parse_slave_ref("1"), stations), 0u);
  EXPECT_EQ(slave_index(parse_slave_ref("3"), stations), 2u);
  EXPECT_EQ(slave_index(parse_slave_ref("0x1002"), stations), 1u);
  try {
    (void)slave_index(parse_slave_ref("4"), stations);
    ADD_FAILURE() << "slave 4 of 3 found";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "there is no slave 4: the line has slaves 1 to 3");
  }
  try {
    (void)slave_index(parse_slave_ref("0x1009"), stations);
    ADD_FAILURE() << "0x1009 found";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "no slave has station address 0x1009 (the line has 0x1001, 0x1002, 0x1003)");
  }
  const std::array<std::uint16_t, 2> unset{0, 0};
  EXPECT_EQ(slave_index(parse_slave_ref("2"), unset), 1u) << "a position needs no address";
  try {
    (void)slave_index(parse_slave_ref("0x1001"), unset);
    ADD_FAILURE() << "0x1001 found before any address was set";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "no slave has station address 0x1001 (no master has set station addresses yet; give the position)");
  }
}

TEST(SlaveRef, TheLabelHasPositionAddressAndProduct) {
  EXPECT_EQ(slave_label(1, 0x1002, "ds5c1"), "slave 2 @0x1002 ds5c1");
  EXPECT_EQ(slave_label(0, 0, "a6b"), "slave 1 a6b");  // before the master sets an address
  EXPECT_EQ(slave_label(2, 0x00AB, ""), "slave 3 @0x00AB");
}

}  // namespace
}  // namespace vdrive::ecat
