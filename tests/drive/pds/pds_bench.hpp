#pragma once
// A real product (profile + dictionary + object values) with a PdsMachine and a StopSequence, and
// an axis moved by hand: tests set the speed the "plant" reports and see what the drive does.
// Units: 1 user unit = 1 motor revolution (factor group all 1), so 30 r/min = 0.5 user units/s.
#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <string>

#include "vdrive/drive/drive_context.hpp"
#include "vdrive/drive/object_ref.hpp"
#include "vdrive/drive/pds/pds_machine.hpp"
#include "vdrive/drive/pds/stop_sequence.hpp"
#include "vdrive/od/dictionary_cache.hpp"
#include "vdrive/od/object_store.hpp"
#include "vdrive/profile/profile_loader.hpp"

namespace vdrive::test {

inline constexpr std::uint16_t kDisableVoltage = 0x0000, kQuickStop = 0x0002, kShutdown = 0x0006,
                               kSwitchOn = 0x0007, kEnable = 0x000F, kFaultReset = 0x0080;

struct PdsBench {
  explicit PdsBench(const std::string& id)
      : product(profile::load_profile(id)),
        dictionary(od::shared_dictionary(product)),
        objects(*dictionary),
        units(one_rev_per_unit()),
        ctx{product, objects, units},
        pds(ctx),
        stop(ctx) {
    pds.power_on();
  }

  static drive::UnitScaling one_rev_per_unit() {
    drive::UnitScaling u;
    u.apply({1, 1, 1, 1, 1, 1, 0});
    return u;
  }

  // Writes an object value as the drive's own code would (no SDO checks: tests also write values
  // the SDO layer would refuse, to see that the drive keeps its previous behaviour).
  void set(std::uint16_t index, std::int64_t value, std::uint8_t sub = 0) {
    drive::ObjectRef<std::int64_t> ref(objects, index, sub);
    ASSERT_TRUE(ref.present()) << std::hex << index;
    ref.set(value);
  }

  // One control step: the axis turns at `speed` (user units/s); conditions as `c` with `stopped`
  // from the stop sequence's threshold.
  void step(std::uint16_t controlword, double speed = 0.0) { step(controlword, speed, base); }
  void step(std::uint16_t controlword, double speed, drive::PdsConditions c) {
    sample.velocity = speed;
    c.stopped = stop.done(sample);
    pds.step(controlword, c);
  }

  // Switch on disabled -> Operation enabled by the usual 6, 7, 15.
  void enable() {
    step(kShutdown);
    step(kSwitchOn);
    step(kEnable);
    ASSERT_EQ(pds.state(), drive::PdsState::OperationEnabled);
  }

  profile::ProductProfile product;
  std::shared_ptr<const od::Dictionary> dictionary;
  od::ObjectStore objects;
  drive::UnitScaling units;
  drive::DriveContext ctx;
  drive::PdsMachine pds;
  drive::StopSequence stop;
  drive::PdsConditions base{};
  drive::AxisSample sample{};
};

}  // namespace vdrive::test
