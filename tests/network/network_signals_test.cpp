// Signals of a network: entries and plant connections read and written from outside, named
// signals, and wires that involve a drive's plant.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "common/clock.hpp"
#include "plant/plant.hpp"
#include "vdrive/network/network.hpp"
#include "vdrive/od/object_store.hpp"

namespace vdrive::network {
namespace {

const std::vector<std::string> kIds = {"a6b", "ds5c1"};

NetworkOptions named(std::vector<SignalWire> wires = {}, std::vector<NamedSignal> signals = {}) {
  NetworkOptions o;
  o.slave_names = {"x", "y"};
  o.wires = std::move(wires);
  o.signals = std::move(signals);
  return o;
}

// Runs timers (control steps, wires) for `duration` in 125 us steps.
void run(Network& net, VirtualClock& clock, Nanos duration) {
  for (Nanos end = clock.now() + duration; clock.now() < end;) {
    clock.advance(125'000);
    net.tick(clock.now());
  }
}

// An entry's bytes as the firmware stores them, little-endian (not through SignalAccess).
std::int64_t stored(Network& net, std::size_t slave, std::uint16_t index, std::uint8_t sub) {
  od::ObjectStore& objects = net.firmware(slave).objects();
  const std::span<const std::uint8_t> raw = objects.raw(*objects.dictionary().find(index, sub));
  std::uint64_t v = 0;
  for (std::size_t i = 0; i < raw.size(); ++i) v |= static_cast<std::uint64_t>(raw[i]) << (8 * i);
  return static_cast<std::int64_t>(v);
}

std::string invalid(Network& net, const std::string& point) {
  try {
    (void)net.resolve(net.parse_point(point));
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no error";
}

TEST(NetworkSignals, AnEntryIsReadAndWrittenAsItsTypeHoldsIt) {
  VirtualClock clock{1'000'000};
  Network net(kIds, clock, named());
  const SignalAccess mode = net.resolve(net.parse_point("x 0x6060:0"));  // I8
  EXPECT_EQ(mode.type_name(), "I8");
  mode.write(-3);
  EXPECT_EQ(mode.read(), -3);
  EXPECT_EQ(stored(net, 0, 0x6060, 0), 0xFD) << "-3 as an I8";
  try {
    mode.write(200);
    FAIL() << "200 does not fit an I8";
  } catch (const std::out_of_range& e) {
    EXPECT_STREQ(e.what(), "200 is outside -128..127");
  }
  EXPECT_EQ(mode.read(), -3) << "a refused write changes nothing";
}

TEST(NetworkSignals, PointsThatCannotCarryASignalAreRefusedWithTheReason) {
  VirtualClock clock{1'000'000};
  Network net(kIds, clock, named());
  EXPECT_EQ(invalid(net, "x 0x7000:1"), "'x' (slave 1, a6b) has no object 7000h:01h");
  EXPECT_EQ(invalid(net, "y 0x1008:0"),
            "'y' (slave 2, ds5c1): 1008h:00h 'Device' is a VS, not an integer a signal can carry");
}

TEST(NetworkSignals, AHomeSwitchActuatedFromOutsideReachesTheDrivesInputs) {
  VirtualClock clock{1'000'000};
  Network net(kIds, clock, named());
  const SignalAccess home = net.resolve(net.parse_point("x.home"));
  EXPECT_EQ(home.read(), 0);
  run(net, clock, 2'000'000);
  EXPECT_EQ(stored(net, 0, 0x60FD, 0) & 0x4u, 0u);
  home.write(1);
  run(net, clock, 2'000'000);
  EXPECT_EQ(home.read(), 1);
  EXPECT_EQ(stored(net, 0, 0x60FD, 0) & 0x4u, 0x4u) << "A6B 60FDh bit 2 HOME";
  home.write(0);
  run(net, clock, 2'000'000);
  EXPECT_EQ(stored(net, 0, 0x60FD, 0) & 0x4u, 0u);
  EXPECT_THROW(home.write(2), std::out_of_range);
}

TEST(NetworkSignals, TheBrakeOutputOfADisabledDriveHoldsTheBrake) {
  VirtualClock clock{1'000'000};
  Network net(kIds, clock, named());
  run(net, clock, 1'000'000);
  EXPECT_EQ(net.resolve(net.parse_point("x.brake_release")).read(), 0);
}

TEST(NetworkSignals, AWireCarriesOneDrivesSwitchToAnotherDrivesInput) {
  VirtualClock clock{1'000'000};
  SignalWire w;
  w.from = parse_signal_point("x.positive_limit", std::vector<std::string>{"x", "y"});
  w.to = parse_signal_point("y.home", std::vector<std::string>{"x", "y"});
  w.name = "test wire";
  Network net(kIds, clock, named({w}));
  net.resolve(net.parse_point("x.positive_limit")).write(1);
  run(net, clock, 2'000'000);
  EXPECT_EQ(net.resolve(net.parse_point("y.home")).read(), 1);
  EXPECT_EQ(stored(net, 1, 0x60FD, 0) & 0x4u, 0x4u) << "DS5C1 60FDh bit 2 HOME";
  net.resolve(net.parse_point("x.positive_limit")).write(0);
  run(net, clock, 2'000'000);
  EXPECT_EQ(stored(net, 1, 0x60FD, 0) & 0x4u, 0u);
}

TEST(NetworkSignals, EntriesOfDifferentSizesCannotBeWired) {
  VirtualClock clock{1'000'000};
  SignalWire w;
  w.from = SignalPoint{0, std::nullopt, 0x6060, 0};
  w.to = SignalPoint{1, std::nullopt, 0x6040, 0};
  w.name = "wires[0]";
  try {
    Network net(kIds, clock, named({w}));
    FAIL() << "an I8 wired to a U16";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "wires[0]: the source is 8 bits, the target 16");
  }
}

TEST(NetworkSignals, NamedSignalsAreResolvedOnceAndNameTheirOriginWhenWrong) {
  VirtualClock clock{1'000'000};
  Network net(kIds, clock, named({}, {{"mode", SignalPoint{0, std::nullopt, 0x6060, 0}, "bench.yaml:9"}}));
  ASSERT_EQ(net.signals().size(), 1u);
  EXPECT_EQ(net.signals()[0].name, "mode");
  net.signal(0).write(8);
  EXPECT_EQ(stored(net, 0, 0x6060, 0), 8);
  EXPECT_EQ(net.format_point(net.signals()[0].point), "x 0x6060:0");
  try {
    Network bad(kIds, clock, named({}, {{"door", SignalPoint{1, std::nullopt, 0x6000, 1}, "bench.yaml:12"}}));
    FAIL() << "6000h does not exist on a DS5C1";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "bench.yaml:12: signal 'door': 'y' (slave 2, ds5c1) has no object 6000h:01h");
  }
}

}  // namespace
}  // namespace vdrive::network
