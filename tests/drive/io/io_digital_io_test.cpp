// DigitalIo on the three products: 60FDh bit layouts, input logic, the din:: bits the drive acts
// on, 60FEh outputs under their mask and the brake rules.
#include "vdrive/drive/io/digital_io.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <string_view>

#include "plant/plant.hpp"
#include "vdrive/drive/drive_types.hpp"
#include "vdrive/od/dictionary_cache.hpp"
#include "vdrive/profile/profile_loader.hpp"

namespace vdrive::drive {
namespace {

namespace in = plant::input;
constexpr std::uint32_t kAllSensors = in::negative_limit | in::positive_limit | in::home | in::probe1 | in::probe2;

class IoBench {
public:
  // `polarity`: 607Eh in force; `edit` adjusts the product's drive rules before the I/O is built.
  explicit IoBench(std::string_view product, std::uint8_t polarity = 0,
                   void (*edit)(profile::ProductProfile&) = nullptr)
      : profile_(profile::load_profile(product)), dict_(od::shared_dictionary(profile_)), store_(*dict_) {
    if (edit) edit(profile_);
    FactorGroup f;
    f.polarity = polarity;
    units_.apply(f);
    io_ = std::make_unique<DigitalIo>(ctx_);
  }

  template <typename T>
  void put(std::uint16_t index, std::uint8_t sub, T value) { ObjectRef<T>(store_, index, sub).set(value); }
  std::uint32_t inputs_object() { return ObjectRef<std::uint32_t>(store_, 0x60FD).get(); }
  DigitalIo& io() { return *io_; }

private:
  profile::ProductProfile profile_;
  std::shared_ptr<const od::Dictionary> dict_;
  od::ObjectStore store_;
  UnitScaling units_;
  DriveContext ctx_{profile_, store_, units_};
  std::unique_ptr<DigitalIo> io_;
};

// ---- Panasonic MINAS-A6B ------------------------------------------------------------------------

TEST(IoDigitalA6b, InputsUseThePanasonicLayout) {
  IoBench b("a6b");
  const std::uint32_t d = b.io().update(kAllSensors, false, false);
  // bit0 NOT, bit1 POT, bit2 HOME, bit19 EXT1, bit20 EXT2 (L27789-L27906)
  EXPECT_EQ(b.inputs_object(), 0x0018'0007u);
  EXPECT_EQ(d, din::negative_limit | din::positive_limit | din::home | din::probe1 | din::probe2);
  b.io().set_in_position(true);  // bit 24 INP
  b.io().update(in::home, false, false);
  EXPECT_EQ(b.inputs_object(), 0x0100'0004u);
}

TEST(IoDigitalA6b, PolaritySwapsPotAndNot) {
  IoBench b("a6b", 0xE0);  // 607Eh = 224: all signs inverted (L28960)
  const std::uint32_t d = b.io().update(in::positive_limit, false, false);
  EXPECT_EQ(b.inputs_object(), 0x0000'0001u);  // NOT (L29021-L29025)
  EXPECT_EQ(d, din::negative_limit);
}

TEST(IoDigitalA6b, Ext1ShowsOnlyWhenSi5CarriesIt) {
  IoBench b("a6b");
  b.put<std::int32_t>(0x3404, 0, 0x00222222);  // SI5 is not EXT1 (L24858)
  const std::uint32_t d = b.io().update(in::probe1 | in::probe2, false, false);
  EXPECT_EQ(b.inputs_object(), 0x0010'0000u);  // EXT2 only
  EXPECT_EQ(d, din::probe2);
}

TEST(IoDigitalA6b, BrakeIsAutomaticAndSetBrakeDefaultsToOnWhenMasked) {
  IoBench b("a6b", 0, [](profile::ProductProfile& p) { p.drive.brake = profile::BrakeRule::Automatic; });
  EXPECT_TRUE(b.io().brake_engaged(false));
  EXPECT_FALSE(b.io().brake_engaged(true));
  b.io().update(0, false, false);
  EXPECT_EQ(b.io().outputs(), 0x0000'0001u);  // masked set brake = 1 (L28118-L28167)
  b.put<std::uint32_t>(0x60FE, 1, 0x0001'0000);  // EX-OUT1 on, set brake off
  b.put<std::uint32_t>(0x60FE, 2, 0x0001'0001);
  b.io().update(0, false, false);
  EXPECT_EQ(b.io().outputs(), 0x0001'0000u);
  b.put<std::uint32_t>(0x60FE, 2, 0x0000'0001);  // EX-OUT1 masked: default 0 (L28090)
  b.io().update(0, false, false);
  EXPECT_EQ(b.io().outputs(), 0x0000'0000u);
}

TEST(IoDigitalA6b, StoInputBecomesTorqueOffWhereTheProductHasOne) {
  IoBench without("a6b", 0, [](profile::ProductProfile& p) { p.drive.torque_off_input = false; });
  EXPECT_EQ(without.io().update(0, true, false), 0u);
  IoBench with("a6b", 0, [](profile::ProductProfile& p) { p.drive.torque_off_input = true; });
  EXPECT_EQ(with.io().update(0, true, false), din::torque_off);
}

// ---- Xinje DS5C1 --------------------------------------------------------------------------------

TEST(IoDigitalDs5c1, InputsUseTheXinjeLayoutAndProbeTerminals) {
  IoBench b("ds5c1");
  b.io().update(kAllSensors, false, false);
  EXPECT_EQ(b.inputs_object(), 0x07u);  // P5-62/P5-63 = 0: no probe terminals (L4701, L4541)
  b.put<std::uint16_t>(0x253E, 0, 1);
  b.put<std::uint16_t>(0x253F, 0, 2);
  b.io().update(kAllSensors, false, false);
  EXPECT_EQ(b.inputs_object(), 0x1Fu);  // bit3 TP1, bit4 TP2 (L10201-L10214)
}

TEST(IoDigitalDs5c1, ZBitStaysOnForP5_19Milliseconds) {
  IoBench b("ds5c1");  // 125 us control steps
  b.io().update(0, false, true);
  EXPECT_EQ(b.inputs_object(), 0x20u);  // bit 5 (L10215)
  for (int i = 1; i < 16; ++i) {
    b.io().update(0, false, false);
    EXPECT_EQ(b.inputs_object(), 0x20u) << "step " << i;
  }
  b.io().update(0, false, false);  // 2 ms = P5-19 factory value (L4771)
  EXPECT_EQ(b.inputs_object(), 0x00u);
  b.put<std::uint16_t>(0x2513, 0, 1);  // P5-19 = 1 ms
  b.io().update(0, false, true);
  for (int i = 1; i < 8; ++i) b.io().update(0, false, false);
  EXPECT_EQ(b.inputs_object(), 0x20u);
  b.io().update(0, false, false);
  EXPECT_EQ(b.inputs_object(), 0x00u);
}

TEST(IoDigitalDs5c1, PolarityLeavesTheTerminalsButTheDriveActsInTheUserFrame) {
  IoBench b("ds5c1", 0xE0);
  const std::uint32_t d = b.io().update(in::positive_limit, false, false);
  EXPECT_EQ(b.inputs_object(), 0x02u);  // POT terminal as wired; only the A6B documents a swap
  EXPECT_EQ(d, din::negative_limit);
}

TEST(IoDigitalDs5c1, OutputsAreValueUnderMask) {
  IoBench b("ds5c1");
  b.put<std::uint32_t>(0x60FE, 1, 0x0007'0000);  // remote SO1-SO3 (L10246)
  b.put<std::uint32_t>(0x60FE, 2, 0x0005'0000);
  b.io().update(0, false, false);
  EXPECT_EQ(b.io().outputs(), 0x0005'0000u);
}

// ---- DS1000A-EC ---------------------------------------------------------------------------------

void ds1000a_rules(profile::ProductProfile& p) {
  p.drive.brake = profile::BrakeRule::Master;  // L3480-L3524
  p.drive.torque_off_input = true;             // TO input -> Switch on disabled (L5566-L5572)
}

TEST(IoDigitalDs1000a, InputsUseTheDs1000aLayout) {
  IoBench b("ds1000a", 0, ds1000a_rules);
  const std::uint32_t d = b.io().update(kAllSensors, true, false);
  // bit0 LM-, bit1 LM+, bit2 ORG, bit3 interlock, bit16 IN1, bit17 IN2 (L3458-L3478)
  EXPECT_EQ(b.inputs_object(), 0x0003'000Fu);
  EXPECT_EQ(d, din::negative_limit | din::positive_limit | din::home | din::probe1 | din::probe2 | din::torque_off);
}

TEST(IoDigitalDs1000a, ActiveLevelSettingsInvertWhatTheDriveDetects) {
  IoBench b("ds1000a", 0, ds1000a_rules);
  b.put<std::uint16_t>(0x215B, 0, 0);  // LM+ active-H, sensor wired for the factory active-L (L4243)
  std::uint32_t d = b.io().update(0, false, false);
  EXPECT_EQ(b.inputs_object(), 0x02u);
  EXPECT_EQ(d, din::positive_limit);
  d = b.io().update(in::positive_limit, false, false);
  EXPECT_EQ(b.inputs_object(), 0x00u);
  b.put<std::uint16_t>(0x215B, 0, 1);
  b.put<std::uint16_t>(0x215C, 0, 0);  // LM- (L4253)
  b.put<std::uint16_t>(0x2162, 0, 0);  // ORG (L4295)
  d = b.io().update(in::negative_limit, false, false);
  EXPECT_EQ(b.inputs_object(), 0x04u);
  EXPECT_EQ(d, din::home);
}

TEST(IoDigitalDs1000a, BrakeStaysEngagedUntilTheMasterUnmasksIt) {
  IoBench b("ds1000a", 0, ds1000a_rules);
  EXPECT_TRUE(b.io().brake_engaged(true));  // initial value 1, mask 00FF0000h (L3507, L3521)
  b.put<std::uint32_t>(0x60FE, 1, 0);
  b.io().update(0, false, false);
  EXPECT_TRUE(b.io().brake_engaged(true));  // masked: the value is not taken
  b.put<std::uint32_t>(0x60FE, 2, 0x00FF'0001);
  b.io().update(0, false, false);
  EXPECT_FALSE(b.io().brake_engaged(true));
  EXPECT_FALSE(b.io().brake_engaged(false));  // the master's output, not the power stage
  b.put<std::uint32_t>(0x60FE, 2, 0x00FF'0000);
  b.put<std::uint32_t>(0x60FE, 1, 1);
  b.io().update(0, false, false);
  EXPECT_FALSE(b.io().brake_engaged(true));  // a masked bit keeps its state (L3517)
  b.put<std::uint32_t>(0x60FE, 2, 0x00FF'0001);
  b.io().update(0, false, false);
  EXPECT_TRUE(b.io().brake_engaged(true));
}

TEST(IoDigitalDs1000a, GeneralOutputsFollowTheFactoryMask) {
  IoBench b("ds1000a", 0, ds1000a_rules);
  b.put<std::uint32_t>(0x60FE, 1, 0x0041'0001);  // OUT1, OUT7, brake
  b.io().update(0, false, false);
  EXPECT_EQ(b.io().outputs(), 0x0041'0001u);
  b.put<std::uint32_t>(0x60FE, 1, 0x0000'0001);
  b.io().update(0, false, false);
  EXPECT_EQ(b.io().outputs(), 0x0000'0001u);
  b.io().power_on();
  EXPECT_EQ(b.io().outputs(), 0x0000'0001u);
}

}  // namespace
}  // namespace vdrive::drive
