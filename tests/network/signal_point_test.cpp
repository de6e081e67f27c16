// Signal points as users write them: "SLAVE INDEX:SUB" or "SLAVE.CONNECTION", slaves by name or
// position from 1; every mistake says what is wrong.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "vdrive/network/signal_point.hpp"

namespace vdrive::network {
namespace {

const std::vector<std::string> kNames = {"coupler", "di", "slave 3", "x"};

TEST(SignalPoint, AnEntryOfASlaveByName) {
  const SignalPoint p = parse_signal_point("di 0x6000:1", kNames);
  EXPECT_EQ(p.slave, 1u);
  EXPECT_FALSE(p.plant);
  EXPECT_EQ(p.index, 0x6000);
  EXPECT_EQ(p.subindex, 1);
}

TEST(SignalPoint, ANameWithASpaceAndDecimalNumbers) {
  const SignalPoint p = parse_signal_point("slave 3 24576:17", kNames);
  EXPECT_EQ(p.slave, 2u);
  EXPECT_EQ(p.index, 0x6000);
  EXPECT_EQ(p.subindex, 0x11);
}

TEST(SignalPoint, APlantConnectionOfASlaveByPosition) {
  const SignalPoint p = parse_signal_point("4.home", kNames);
  EXPECT_EQ(p.slave, 3u);
  ASSERT_TRUE(p.plant);
  EXPECT_EQ(*p.plant, PlantConnection::home);
  EXPECT_EQ(parse_signal_point("x.brake_release", kNames).plant, PlantConnection::brake_release);
}

TEST(SignalPoint, FormattedAsItIsParsed) {
  for (const std::string text : {"di 0x6000:1", "x.probe2", "slave 3 0x7010:17"})
    EXPECT_EQ(format_signal_point(parse_signal_point(text, kNames), kNames), text);
  SignalPoint unnamed;
  unnamed.slave = 6;
  unnamed.plant = PlantConnection::negative_limit;
  EXPECT_EQ(format_signal_point(unnamed, kNames), "7.negative_limit");
}

std::string error_of(const std::string& text) {
  try {
    (void)parse_signal_point(text, kNames);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no error";
}

TEST(SignalPoint, MistakesSayWhatIsWrong) {
  EXPECT_EQ(error_of("di"), "'di': expected SLAVE INDEX:SUBINDEX (e.g. 'do 0x7000:1') or SLAVE.CONNECTION (e.g. 'x.home')");
  EXPECT_EQ(error_of("do 0x7000:1"), "'do 0x7000:1': no slave 'do' (names: coupler, di, slave 3, x; or a position 1-4)");
  EXPECT_EQ(error_of("x.hom"), "'x.hom': no plant connection 'hom' (connections: negative_limit, positive_limit, home, "
                               "probe1, probe2, brake_release)");
  EXPECT_EQ(error_of("di 0x6000"), "'di 0x6000': the entry is INDEX:SUBINDEX, e.g. 0x7000:1");
  EXPECT_EQ(error_of("di 0x6000:256"), "'di 0x6000:256': the entry is INDEX:SUBINDEX, e.g. 0x7000:1");
  EXPECT_EQ(error_of("5.home"), "'5.home': no slave '5' (names: coupler, di, slave 3, x; or a position 1-4)");
}

}  // namespace
}  // namespace vdrive::network
