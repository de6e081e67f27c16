// TouchProbe on the three products with hand-made input sequences: the axis moves 100 user units
// per 125 us step (step k ends at position 100 k, DC time T0 + k * 125 us), so an input edge seen
// in step k is latched at 100 k - 50 and time T0 + k * 125 us - 62.5 us (midpoint of the step).
#include "vdrive/drive/io/touch_probe.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <string_view>

#include "plant/plant.hpp"
#include "vdrive/od/dictionary_cache.hpp"
#include "vdrive/profile/profile_loader.hpp"

namespace vdrive::drive {
namespace {

namespace in = plant::input;
constexpr std::uint64_t kT0 = 5'000'000'000;   // above 2^32: time stamps keep the low 32 bits
constexpr std::uint64_t kStepNs = 125'000;

class ProbeBench {
public:
  explicit ProbeBench(std::string_view product)
      : profile_(profile::load_profile(product)), dict_(od::shared_dictionary(profile_)), store_(*dict_) {
    units_.apply({});
    probe_ = std::make_unique<TouchProbe>(ctx_);
  }

  template <typename T>
  void put(std::uint16_t index, std::uint8_t sub, T value) { ObjectRef<T>(store_, index, sub).set(value); }
  std::int64_t get(std::uint16_t index, std::uint8_t sub = 0) {
    return ObjectRef<std::int64_t>(store_, index, sub).get();
  }
  std::uint16_t status() { return static_cast<std::uint16_t>(get(0x60B9)); }
  void function(std::uint16_t value) { put<std::uint16_t>(0x60B8, 0, value); }
  void mode(std::int8_t value) { put<std::int8_t>(0x6061, 0, value); }

  // One step ending at position 100 k with `inputs` (plant::input bits) at its end.
  void step(std::uint32_t inputs, bool index = false, double index_position = 0.0) {
    ++k_;
    AxisSample s;
    s.position = 100.0 * k_;
    s.index_passed = index;
    s.index_position = index_position;
    probe_->step(inputs_, inputs, s, kT0 + k_ * kStepNs);
    inputs_ = inputs;
  }
  TouchProbe& probe() { return *probe_; }
  const profile::ProductProfile& profile() const { return profile_; }

private:
  profile::ProductProfile profile_;
  std::shared_ptr<const od::Dictionary> dict_;
  od::ObjectStore store_;
  UnitScaling units_;
  DriveContext ctx_{profile_, store_, units_};
  std::unique_ptr<TouchProbe> probe_;
  std::uint32_t inputs_ = 0;
  std::uint64_t k_ = 0;
};

// ---- Panasonic MINAS-A6B ------------------------------------------------------------------------

TEST(IoTouchProbeA6b, FirstEventLatchesTheFirstRisingEdgeOnlyUntilRestarted) {
  ProbeBench b("a6b");
  b.function(0x0011);  // TP1 on, first event, EXT1, rising (L25158-L25260)
  b.step(0);
  EXPECT_EQ(b.status(), 0x0001);
  b.step(in::probe1);  // step 2: edge -> 150
  EXPECT_EQ(b.get(0x60BA), 150);
  EXPECT_EQ(b.status(), 0x0003);
  b.step(0);
  b.step(in::probe1);  // a second rising edge: first-event mode ignores it (L25638-L25644)
  EXPECT_EQ(b.get(0x60BA), 150);
  b.function(0x0000);  // stop: 60B9h cleared, the value stays
  b.step(in::probe1);
  EXPECT_EQ(b.status(), 0x0000);
  EXPECT_EQ(b.get(0x60BA), 150);
  b.function(0x0011);  // 0 -> 1 restarts (L25619-L25621)
  b.step(0);
  EXPECT_EQ(b.status(), 0x0001);
  b.step(in::probe1);  // step 7 -> 650
  EXPECT_EQ(b.get(0x60BA), 650);
  EXPECT_EQ(b.status(), 0x0003);
}

TEST(IoTouchProbeA6b, BothEdgesInFirstEventModeLatchEachOnce) {
  ProbeBench b("a6b");
  b.function(0x0031);  // rising and falling together on an external input (L25235, L25644)
  b.step(0);
  b.step(in::probe1);  // step 2 rising -> 150
  b.step(in::probe1);
  b.step(0);           // step 4 falling -> 350
  EXPECT_EQ(b.get(0x60BA), 150);
  EXPECT_EQ(b.get(0x60BB), 350);
  EXPECT_EQ(b.status(), 0x0007);
  b.step(in::probe1);
  b.step(0);
  EXPECT_EQ(b.get(0x60BA), 150);
  EXPECT_EQ(b.get(0x60BB), 350);
}

TEST(IoTouchProbeA6b, ContinuousModeLatchesEveryEdgeAnd3697hBit13TogglesTheStoredBit) {
  ProbeBench b("a6b");
  b.function(0x0013);  // continuous, rising (L25794-L25800)
  b.step(0);
  b.step(in::probe1);  // step 2 -> 150
  EXPECT_EQ(b.get(0x60BA), 150);
  b.step(0);
  b.step(0);
  b.step(in::probe1);  // step 5 -> 450
  EXPECT_EQ(b.get(0x60BA), 450);
  EXPECT_EQ(b.status(), 0x0003);  // bit 1 stays set without the toggle option
  EXPECT_EQ(b.get(0x60D5), 0);    // the A6B has no edge counters

  b.put<std::int32_t>(0x3697, 0, 1 << 13);  // toggle on each latch (L25802)
  b.function(0);
  b.step(0);
  b.function(0x0013);
  b.step(0);
  b.step(in::probe1);
  EXPECT_EQ(b.status(), 0x0003);
  b.step(0);
  b.step(in::probe1);
  EXPECT_EQ(b.status(), 0x0001);
  b.step(0);
  b.step(in::probe1);
  EXPECT_EQ(b.status(), 0x0003);
}

TEST(IoTouchProbeA6b, ZPhaseTriggerLatchesAtTheIndexPosition) {
  ProbeBench b("a6b");
  b.function(0x0015);  // bit 2 = 1: Z phase (L25158-L25260)
  b.step(0);
  b.step(in::probe1);  // EXT1 is not the trigger now
  EXPECT_EQ(b.status(), 0x0001);
  b.step(0, /*index=*/true, 225.0);
  EXPECT_EQ(b.get(0x60BA), 225);
  EXPECT_EQ(b.status(), 0x0003);
}

TEST(IoTouchProbeA6b, ChannelTwoUsesExt2AndTheUpperBits) {
  ProbeBench b("a6b");
  b.function(0x1100);  // TP2 on, rising
  b.step(0);
  b.step(in::probe1);  // EXT1 does not trigger TP2
  EXPECT_EQ(b.status(), 0x0100);
  b.step(in::probe1 | in::probe2);  // step 3 -> 250
  EXPECT_EQ(b.get(0x60BC), 250);
  EXPECT_EQ(b.get(0x60BA), 0);
  EXPECT_EQ(b.status(), 0x0300);
}

TEST(IoTouchProbeA6b, SettingsAreTakenOverOnlyAtTheStartEdge) {
  ProbeBench b("a6b");
  b.function(0x0011);
  b.step(0);
  b.function(0x0021);  // falling only, written while running: ignored (L25619-L25621)
  b.step(in::probe1);  // step 2 rising still latches -> 150
  b.step(0);
  EXPECT_EQ(b.get(0x60BA), 150);
  EXPECT_EQ(b.get(0x60BB), 0);
  EXPECT_EQ(b.status(), 0x0003);
}

TEST(IoTouchProbeA6b, SwitchingToHomingAndEsmInitCancel) {
  ProbeBench b("a6b");
  b.mode(mode::pp);
  b.function(0x0013);
  b.step(0);
  b.step(in::probe1);
  EXPECT_EQ(b.status(), 0x0003);
  b.mode(mode::hm);  // L24736
  b.step(0);
  EXPECT_EQ(b.status(), 0x0000);
  b.step(in::probe1);  // 60B8h bit 0 still 1: no new start without 0 -> 1
  EXPECT_EQ(b.status(), 0x0000);
  b.function(0);
  b.step(0);
  b.function(0x0013);  // the A6B probe runs in hm once restarted
  b.step(0);
  EXPECT_EQ(b.status(), 0x0001);
  b.probe().cancel();  // ESM Init (L24734)
  EXPECT_EQ(b.status(), 0x0000);
  b.step(in::probe1);
  EXPECT_EQ(b.status(), 0x0000);
}

TEST(IoTouchProbeA6b, ExternalInputWithoutSi5AssignmentRaisesErr88_3) {
  ProbeBench b("a6b");
  ASSERT_NE(b.profile().find_alarm("88.3"), nullptr);
  b.put<std::int32_t>(0x3404, 0, 0x00222222);  // SI5 carries HOME, not EXT1 (L24704-L24706)
  b.function(0x0015);                           // Z trigger needs no terminal
  b.step(0);
  EXPECT_EQ(b.probe().pending_alarm(), "");
  EXPECT_EQ(b.status(), 0x0001);
  b.function(0);
  b.step(0);
  b.function(0x0011);
  b.step(0);
  EXPECT_EQ(b.probe().pending_alarm(), "88.3");
  EXPECT_EQ(b.probe().pending_alarm(), "");  // reported once
  EXPECT_EQ(b.status(), 0x0000);
  b.step(in::probe1);
  EXPECT_EQ(b.get(0x60BA), 0);
  b.put<std::int32_t>(0x3404, 0, 0x00A0A0A0);  // EXT1 normally closed (L24858-L24860)
  b.function(0);
  b.step(0);
  b.function(0x0011);
  b.step(0);
  EXPECT_EQ(b.probe().pending_alarm(), "");
  b.step(in::probe1);
  EXPECT_EQ(b.status(), 0x0003);
}

// ---- Xinje DS5C1 --------------------------------------------------------------------------------

TEST(IoTouchProbeDs5c1, FactoryTerminalAssignmentRaisesE883) {
  ProbeBench b("ds5c1");
  ASSERT_NE(b.profile().find_alarm("E-883"), nullptr);
  b.function(0x0011);  // P5-62 = 0 at the factory on most models (L4541-L4548)
  b.step(0);
  EXPECT_EQ(b.probe().pending_alarm(), "E-883");  // L4554
  EXPECT_EQ(b.status(), 0x0000);
}

TEST(IoTouchProbeDs5c1, BothEdgesSetArmTheRisingEdgeOnly) {
  ProbeBench b("ds5c1");
  b.put<std::uint16_t>(0x253E, 0, 1);  // P5-62: probe 1 on SI1 (L4541)
  b.function(0x0031);                   // both edges: "do not" (L4566)
  b.step(0);
  EXPECT_EQ(b.probe().pending_alarm(), "");
  b.step(in::probe1);  // step 2 -> 150
  b.step(0);
  EXPECT_EQ(b.get(0x60BA), 150);
  EXPECT_EQ(b.get(0x60BB), 0);
  EXPECT_EQ(b.status(), 0x0003);
}

TEST(IoTouchProbeDs5c1, ZPhaseTriggerIsNotSupported) {
  ProbeBench b("ds5c1");
  b.function(0x0015);  // L10056: Z "not supported"
  b.step(0);
  b.step(0, true, 150.0);
  EXPECT_EQ(b.probe().pending_alarm(), "");
  EXPECT_EQ(b.get(0x60BA), 0);
  EXPECT_EQ(b.status(), 0x0001);
}

TEST(IoTouchProbeDs5c1, NoProbeInHomingAndEveryModeChangeCancels) {
  ProbeBench b("ds5c1");
  b.put<std::uint16_t>(0x253E, 0, 1);
  b.mode(mode::hm);
  b.function(0x0011);
  b.step(0);
  EXPECT_EQ(b.status(), 0x0000);  // L4516
  b.mode(mode::csp);
  b.step(0);
  EXPECT_EQ(b.status(), 0x0000);  // a new start is needed (L4672)
  b.function(0);
  b.step(0);
  b.function(0x0011);
  b.step(0);
  EXPECT_EQ(b.status(), 0x0001);
  b.mode(mode::pp);
  b.step(in::probe1);
  EXPECT_EQ(b.status(), 0x0000);
  EXPECT_EQ(b.get(0x60BA), 0);
}

// ---- DS1000A-EC ---------------------------------------------------------------------------------

TEST(IoTouchProbeDs1000a, ContinuousModeCountsEdgesAndStampsDcTime) {
  ProbeBench b("ds1000a");
  b.function(0x0033);  // TP1 on, continuous, IN1 (bits 3-2 = 00), both edges (L3601-L3635)
  b.step(0);
  b.step(in::probe1);  // step 2 rising -> 150
  b.step(in::probe1);
  b.step(0);           // step 4 falling -> 350
  b.step(0);
  b.step(0);
  b.step(in::probe1);  // step 7 rising -> 650
  EXPECT_EQ(b.get(0x60BA), 650);
  EXPECT_EQ(b.get(0x60BB), 350);
  EXPECT_EQ(b.get(0x60D5), 2);  // L3817-L3821
  EXPECT_EQ(b.get(0x60D6), 1);
  EXPECT_EQ(b.get(0x60D1), 705'845'204);  // (T0 + 812.5 us) mod 2^32 (L3793-L3795)
  EXPECT_EQ(b.get(0x60D2), 705'470'204);  // (T0 + 437.5 us) mod 2^32
  EXPECT_EQ(b.status(), 0x0007);
}

TEST(IoTouchProbeDs1000a, FirstEventStampsButDoesNotCount) {
  ProbeBench b("ds1000a");
  b.function(0x0011);
  b.step(0);
  b.step(in::probe1);
  EXPECT_EQ(b.get(0x60D1), 705'220'204);  // (T0 + 187.5 us) mod 2^32
  EXPECT_EQ(b.get(0x60D5), 0);            // counters count in continuous mode only (L3819)
}

TEST(IoTouchProbeDs1000a, EdgeCounterWrapsAfter65535) {
  ProbeBench b("ds1000a");
  b.put<std::uint16_t>(0x60D5, 0, 65535);
  b.function(0x0013);
  b.step(0);
  b.step(in::probe1);
  EXPECT_EQ(b.get(0x60D5), 0);  // L3821
}

TEST(IoTouchProbeDs1000a, SoftwareEncoderZeroLatchesRisingOnlyAtTheIndex) {
  ProbeBench b("ds1000a");
  b.function(0x0035);  // bits 3-2 = 01 software encoder zero, both edges requested (L3621)
  b.step(0);
  b.step(0);
  b.step(0, true, 225.0);  // step 3: 200 -> 300, a quarter of the way
  EXPECT_EQ(b.get(0x60BA), 225);
  EXPECT_EQ(b.get(0x60D1), 705'313'954);  // (T0 + 250 us + 31.25 us) mod 2^32
  EXPECT_EQ(b.get(0x60BB), 0);            // rising only (L3532-L3534)
  EXPECT_EQ(b.status(), 0x0003);
}

TEST(IoTouchProbeDs1000a, Source60D0hOrgFollowsTheHomeLogicSetting) {
  ProbeBench b("ds1000a");
  b.put<std::int16_t>(0x60D0, 1, -3);  // ORG (L3769)
  b.function(0x0019);                  // bits 3-2 = 10: 60D0h source, rising
  b.step(0);
  b.step(in::home);  // step 2 -> 150
  EXPECT_EQ(b.get(0x60BA), 150);

  b.put<std::uint16_t>(0x2162, 0, 0);  // ORG active-H: the actuated sensor now reads "not detected"
  b.function(0);
  b.step(in::home);
  b.function(0x0019);
  b.step(in::home);
  b.step(0);  // step 5: sensor released = detected rising edge -> 450
  EXPECT_EQ(b.get(0x60BA), 450);
}

TEST(IoTouchProbeDs1000a, UnsupportedAndReservedSourcesNeverLatch) {
  ProbeBench b("ds1000a");
  b.put<std::int16_t>(0x60D0, 1, 5);  // encoder Z: not supported (L3785)
  b.function(0x0019);
  b.step(0);
  b.step(in::probe1, true, 150.0);
  EXPECT_EQ(b.get(0x60BA), 0);
  b.function(0);
  b.step(0);
  b.function(0x001D);  // bits 3-2 = 11: reserved (L3625)
  b.step(0);
  b.step(in::probe1, true, 450.0);
  EXPECT_EQ(b.get(0x60BA), 0);
  EXPECT_EQ(b.status(), 0x0001);
}

TEST(IoTouchProbeDs1000a, ChannelTwoDefaultsToIn2AndCanWatchTheInterlock) {
  ProbeBench b("ds1000a");
  b.function(0x1100);  // bits 11-10 = 00: IN2 (L3651)
  b.step(0);
  b.step(in::probe2);  // step 2 -> 150
  EXPECT_EQ(b.get(0x60BC), 150);
  b.put<std::int16_t>(0x60D0, 2, -4);  // interlock, the inverted TO input (L3767)
  b.function(0);
  b.step(0);
  b.function(0x1900);
  b.step(0);
  b.step(din::torque_off);  // step 5: TO opens -> 450
  EXPECT_EQ(b.get(0x60BC), 450);
  EXPECT_EQ(b.status(), 0x0300);
}

}  // namespace
}  // namespace vdrive::drive
