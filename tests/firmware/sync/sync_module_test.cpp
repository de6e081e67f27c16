// The sync module on a real ESC (registers written ECAT-side, as a master does) and the product's
// real object dictionary: PreOp->SafeOp answers, the cyclic task on SYNC0, lock supervision,
// counters and 1C32h/1C33h contents. Time is virtual; the loop below drives ESC and module the
// way Network/event loop do (ESC tick, PDI IRQ, module timer).
#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "common/clock.hpp"
#include "esc_model/esc.hpp"
#include "tests/esc_model/esc_test_util.hpp"
#include "vdrive/firmware/al_state_machine.hpp"
#include "vdrive/firmware/pdi.hpp"
#include "vdrive/firmware/sync/sync_module.hpp"
#include "vdrive/od/dictionary_cache.hpp"
#include "vdrive/od/object_store.hpp"
#include "vdrive/profile/profile_loader.hpp"
#include "vdrive/profile/sii_image.hpp"
#include "tests/support/allocation_counter.hpp"


namespace vdrive::firmware::sync {
namespace {

namespace cmd = esc::test::cmd;
using esc::test::Frame;
constexpr Nanos kMs = 1000000;

std::vector<std::uint8_t> le(std::uint64_t v, int bytes) {
  std::vector<std::uint8_t> out;
  for (int i = 0; i < bytes; ++i) out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  return out;
}

// One drive: ESC + object store + sync module, nothing else of the firmware.
class Drive {
public:
  explicit Drive(const char* id)
      : profile_(profile::load_profile(id)),
        esc_(profile::make_esc_config(profile_), clock_),
        pdi_(esc_),
        dictionary_(od::shared_dictionary(profile_)),
        objects_(*dictionary_),
        esm_(EsmTraits::of(profile_)),
        module_(std::make_unique<SyncModule>(FirmwareContext{profile_, pdi_, objects_, esm_})) {
    module_->power_on(clock_.now());
    pdi_.write_u32(reg::kAlEventMask, module_->serviced_events());
    module_->on_cycle([this](Nanos t) { cycle_times.push_back(t); });
    module_->on_start([this](SyncMode m) { started.push_back(m); });
    cycle_times.reserve(100000);
  }

  // ECAT-side register access (auto-increment address 0: the only slave).
  void write(std::uint16_t address, std::vector<std::uint8_t> data) {
    Frame f;
    f.add(cmd::APWR, Frame::ap(0, address), std::move(data));
    send(f);
    ASSERT_EQ(f.wkc(0), 1) << std::hex << address;
  }
  std::uint64_t read(std::uint16_t address, int bytes) {
    Frame f;
    f.add(cmd::APRD, Frame::ap(0, address), std::vector<std::uint8_t>(static_cast<std::size_t>(bytes), 0));
    send(f);
    std::uint64_t v = 0;
    const auto d = f.data(0);
    for (int i = bytes; i-- > 0;) v = (v << 8) | d[static_cast<std::size_t>(i)];
    return v;
  }

  // The master's DC SYNC0 programming: cycle, start `lead` ahead of now, then activation.
  void program_sync0(std::uint32_t cycle, std::uint8_t activation = 0x03, Nanos lead = 20 * kMs) {
    write(0x0981, {0x00});
    write(0x09A0, le(cycle, 4));
    write(0x0990, le(read(0x0910, 8) + static_cast<std::uint64_t>(lead), 8));
    write(0x0981, {activation});
  }

  // An SDO-style (checked) object write in PreOp.
  void sdo_write(std::uint16_t index, std::uint8_t subindex, std::uint64_t value) {
    const od::EntryDesc* e = dictionary_->find(index, subindex);
    ASSERT_NE(e, nullptr);
    const auto bytes = le(value, std::max(1, e->bit_length / 8));
    ASSERT_EQ(objects_.write(index, subindex, bytes, ecat::AlState::PreOp), od::SdoAbort::Ok)
        << std::hex << index << ":" << int(subindex);
  }
  std::uint64_t object(std::uint16_t index, std::uint8_t subindex) {
    const od::EntryDesc* e = dictionary_->find(index, subindex);
    if (e == nullptr) return 0;
    std::array<std::uint8_t, 8> buf{};
    std::size_t n = 0;
    EXPECT_EQ(objects_.read(index, subindex, buf, n, ecat::AlState::PreOp), od::SdoAbort::Ok);
    std::uint64_t v = 0;
    for (std::size_t i = n; i-- > 0;) v = (v << 8) | buf[i];
    return v;
  }

  CheckResult request_safeop() {
    const CheckResult r = module_->check_transition(ecat::AlState::PreOp, ecat::AlState::SafeOp);
    if (r.ok()) enter(ecat::AlState::PreOp, ecat::AlState::SafeOp);
    return r;
  }
  void enter(ecat::AlState from, ecat::AlState to) {
    state = to;
    module_->entered(from, to, clock_.now());
  }

  // Runs ESC and module timers and IRQs up to `until`, as the event loop would. Faults are
  // applied like SlaveFirmware does (state change + entered()).
  void run_until(Nanos until) {
    for (;;) {
      const Nanos next = std::min(esc_.next_deadline(), module_->next_deadline());
      if (next > until) break;
      clock_.set(std::max(next, clock_.now()));
      const Nanos now = clock_.now();
      if (esc_.next_deadline() <= now) esc_.tick(now);
      if (esc_.pdi_irq() != 0) module_->on_events(pdi_.read_u32(reg::kAlEventRequest), now);
      apply_fault();
      if (module_->next_deadline() <= now) module_->tick(now);
      apply_fault();
    }
    clock_.set(std::max(until, clock_.now()));
  }
  void apply_fault() {
    FirmwareModule::Fault f;
    if (!module_->take_fault(f)) return;
    faults.push_back(f);
    if (f.state != state) enter(state, f.state);
  }

  Nanos now() const { return clock_.now(); }
  SyncModule& module() { return *module_; }

  std::vector<Nanos> cycle_times;
  std::vector<SyncMode> started;
  std::vector<FirmwareModule::Fault> faults;
  ecat::AlState state = ecat::AlState::PreOp;

private:
  void send(Frame& f) {
    esc::FrameTiming timing;
    timing.port0_rx = clock_.now();
    ASSERT_TRUE(esc_.process_frame(f.pdu(), timing));
  }

  VirtualClock clock_{3 * kMs};
  profile::ProductProfile profile_;
  esc::Esc esc_;
  Pdi pdi_;
  std::shared_ptr<const od::Dictionary> dictionary_;
  od::ObjectStore objects_;
  AlStateMachine esm_;
  std::unique_ptr<SyncModule> module_;
};

// ---- power-on values -----------------------------------------------------------------------

TEST(SyncModule, A6bObjectsHoldTheManualsValues) {
  Drive d("a6b");
  EXPECT_EQ(d.object(0x1C32, 0x00), 0x20u);
  EXPECT_EQ(d.object(0x1C32, 0x04), 0x0007u);    // L7800-L7830
  EXPECT_EQ(d.object(0x1C33, 0x04), 0x0027u);    // input shift supported
  EXPECT_EQ(d.object(0x1C32, 0x05), 125000u);
  EXPECT_EQ(d.object(0x1C32, 0x06), 25000u);
  EXPECT_EQ(d.object(0x1C33, 0x06), 45000u);     // L8119-L8123
  EXPECT_EQ(d.object(0x1C32, 0x09), 0u);
}

TEST(SyncModule, Ds1000aObjectsHoldTheManualsValues) {
  Drive d("ds1000a");
  EXPECT_EQ(d.object(0x1C32, 0x05), 1000000u);   // L4730
  EXPECT_EQ(d.object(0x1C32, 0x06), 125000u);    // L4732
  EXPECT_EQ(d.object(0x1C33, 0x05), 1000000u);
  EXPECT_EQ(d.object(0x1C32, 0x01), 0u);
}

// ---- SYNC0 drives the cyclic task ----------------------------------------------------------

TEST(SyncModule, EverySync0PulseRunsTheCyclicTaskOnceAtEachAllowedA6bCycle) {
  for (std::uint32_t cycle : {125000u, 250000u, 500000u, 1000000u, 2000000u, 4000000u, 8000000u, 10000000u}) {
    Drive d("a6b");
    d.sdo_write(0x1C32, 0x02, cycle);
    d.program_sync0(cycle);
    ASSERT_TRUE(d.request_safeop().ok()) << cycle;
    EXPECT_EQ(d.module().mode(), SyncMode::DcSync0);
    EXPECT_EQ(d.started, std::vector<SyncMode>{SyncMode::DcSync0});
    EXPECT_EQ(d.object(0x1C32, 0x01), 0x02u);       // rewritten from 0981h (factory 00h)
    EXPECT_EQ(d.object(0x1C33, 0x01), 0x02u);
    EXPECT_EQ(d.object(0x1C32, 0x0A), cycle);       // = 09A0h in DC mode
    EXPECT_EQ(d.object(0x1C33, 0x02), cycle);       // copy of 1C32h-02h
    const Nanos start = d.now();
    d.run_until(start + 20 * kMs + 200 * static_cast<Nanos>(cycle) + cycle / 2);
    ASSERT_EQ(d.cycle_times.size(), 201u) << cycle;  // pulses at +20 ms, then every cycle
    for (std::size_t i = 1; i < d.cycle_times.size(); ++i)
      ASSERT_EQ(d.cycle_times[i] - d.cycle_times[i - 1], static_cast<Nanos>(cycle)) << i;
    EXPECT_TRUE(d.module().locked());
    EXPECT_TRUE(d.faults.empty());
  }
}

TEST(SyncModule, Sync0CyclesDoNotAllocate) {
  Drive d("ds5c1");
  d.sdo_write(0x1C32, 0x01, 2);
  d.sdo_write(0x1C33, 0x01, 2);
  d.sdo_write(0x1C32, 0x02, 1000000);
  d.program_sync0(1000000);
  ASSERT_TRUE(d.request_safeop().ok());
  d.run_until(d.now() + 30 * kMs);   // locked, vectors warmed up
  const long before = vdrive::test::allocation_count();
  d.run_until(d.now() + 500 * kMs);
  EXPECT_EQ(vdrive::test::allocation_count(), before);
  EXPECT_GT(d.cycle_times.size(), 500u);
}

TEST(SyncModule, SyncErrorsBeforeSafeOpAreAnsweredWithEachProductsCode) {
  struct Case {
    const char* id;
    std::uint32_t sync0;
    std::uint8_t activation;
    std::uint16_t out_type, in_type;
    std::uint16_t code;
  };
  const Case cases[] = {
      {"a6b", 300000, 0x03, 2, 2, 0x0035},      // Err81.0 cycle not in the list
      {"a6b", 1000000, 0x07, 2, 2, 0x0030},     // Err81.5 SYNC1
      {"a6b", 1000000, 0x03, 3, 2, 0x0028},     // Err81.6 DC SYNC1 mode
      {"ds5c1", 500000, 0x03, 2, 2, 0x0035},    // E-810
      {"ds5c1", 1000000, 0x05, 2, 2, 0x0030},   // E-815
      {"ds5c1", 1000000, 0x03, 2, 0x22, 0x0028},  // E-816
      {"ds1000a", 1500000, 0x03, 2, 2, 0x0035},
      {"ds1000a", 2000000, 0x07, 2, 2, 0x0030},
      {"ds1000a", 2000000, 0x03, 3, 2, 0x0028},
  };
  for (const Case& c : cases) {
    Drive d(c.id);
    d.sdo_write(0x1C32, 0x01, c.out_type);
    d.sdo_write(0x1C33, 0x01, c.in_type);
    if (std::string(c.id) != "ds1000a") d.sdo_write(0x1C32, 0x02, c.sync0);
    d.program_sync0(c.sync0, c.activation);
    const CheckResult r = d.request_safeop();
    EXPECT_EQ(r.code, c.code) << c.id << " 09A0h=" << c.sync0 << " 0981h=" << int(c.activation);
    EXPECT_EQ(r.fallback, ecat::AlState::PreOp) << c.id;
    EXPECT_FALSE(d.module().running());
  }
}

TEST(SyncModule, AllowedCyclesAcceptedPerProduct) {
  const std::pair<const char*, std::vector<std::uint32_t>> products[] = {
      {"ds5c1", {1000000, 2000000, 4000000, 8000000, 10000000}},
      {"ds1000a", {1000000, 2000000, 3000000, 5000000, 10000000}},
  };
  for (const auto& [id, cycles] : products) {
    for (std::uint32_t cycle : cycles) {
      Drive d(id);
      d.sdo_write(0x1C32, 0x01, 2);
      d.sdo_write(0x1C33, 0x01, 2);
      if (std::string(id) == "ds5c1") d.sdo_write(0x1C32, 0x02, cycle);
      d.program_sync0(cycle);
      EXPECT_TRUE(d.request_safeop().ok()) << id << " " << cycle;
      EXPECT_EQ(d.object(0x1C32, 0x02), cycle) << id;   // DS1000A: 02h ro, copied from 09A0h
      d.run_until(d.now() + 20 * kMs + 10 * static_cast<Nanos>(cycle) + cycle / 2);
      EXPECT_EQ(d.cycle_times.size(), 11u) << id << " " << cycle;
    }
  }
}

TEST(SyncModule, A6bSync0CycleDifferentFrom1C32CycleIsRefused) {
  Drive d("a6b");
  d.sdo_write(0x1C32, 0x02, 2000000);
  d.program_sync0(1000000);
  EXPECT_EQ(d.request_safeop().code, 0x0035);
}

// ---- lock supervision -------------------------------------------------------------------------

TEST(SyncModule, NoSync0AfterSafeOpIsNoLockWithin1sThenPreOp) {
  Drive d("a6b");
  d.sdo_write(0x1C32, 0x02, 1000000);
  d.program_sync0(1000000, 0x03, -5 * kMs);   // start time in the past: no pulse ever comes
  ASSERT_TRUE(d.request_safeop().ok());
  const Nanos safeop = d.now();
  d.run_until(safeop + 999 * kMs);
  EXPECT_TRUE(d.faults.empty());
  d.run_until(safeop + 1001 * kMs);
  ASSERT_EQ(d.faults.size(), 1u);
  EXPECT_EQ(d.faults[0].code, 0x002D);            // Err80.3
  EXPECT_EQ(d.faults[0].state, ecat::AlState::PreOp);
  EXPECT_FALSE(d.module().running());
}

TEST(SyncModule, A6bLostSync0IsSyncErrorAfter3742hMissesAndCountedIn4F78h) {
  Drive d("a6b");
  d.sdo_write(0x3742, 0x00, 3);                   // Err80.7 threshold: 3 consecutive misses
  d.sdo_write(0x1C32, 0x02, 1000000);
  d.program_sync0(1000000);
  ASSERT_TRUE(d.request_safeop().ok());
  d.enter(ecat::AlState::SafeOp, ecat::AlState::Op);
  d.run_until(d.now() + 40 * kMs);
  ASSERT_TRUE(d.module().locked());
  const std::size_t cycles = d.cycle_times.size();
  d.write(0x0981, {0x00});                        // the master stops SYNC0
  d.run_until(d.now() + 10 * kMs);
  ASSERT_EQ(d.faults.size(), 1u);
  EXPECT_EQ(d.faults[0].code, 0x002C);
  EXPECT_EQ(d.faults[0].state, ecat::AlState::SafeOp);
  EXPECT_EQ(d.state, ecat::AlState::SafeOp);
  EXPECT_EQ(d.cycle_times.size(), cycles);
  EXPECT_EQ(d.object(0x4F78, 0x00), 3u);
}

TEST(SyncModule, A6bThresholdZeroNeverReportsLostSync) {
  Drive d("a6b");
  d.sdo_write(0x3742, 0x00, 0);
  d.sdo_write(0x1C32, 0x02, 1000000);
  d.program_sync0(1000000);
  ASSERT_TRUE(d.request_safeop().ok());
  d.run_until(d.now() + 40 * kMs);
  ASSERT_TRUE(d.module().locked());
  d.write(0x0981, {0x00});
  d.run_until(d.now() + 200 * kMs);
  EXPECT_TRUE(d.faults.empty());
  EXPECT_GE(d.object(0x4F78, 0x00), 199u);
}

TEST(SyncModule, Ds1000aCountsMissedEventsWithoutLosingSync) {
  // The DS1000A-EC documents the counters (L4742-L4753) but no lost-sync alarm or threshold.
  Drive d("ds1000a");
  d.sdo_write(0x1C32, 0x01, 2);
  d.sdo_write(0x1C33, 0x01, 2);
  d.program_sync0(2000000);
  ASSERT_TRUE(d.request_safeop().ok());
  d.run_until(d.now() + 40 * kMs);
  ASSERT_TRUE(d.module().locked());
  d.write(0x0981, {0x00});
  d.run_until(d.now() + 7 * kMs);                  // misses due at +3, +5, +7 ms after the last pulse
  EXPECT_TRUE(d.faults.empty());
  EXPECT_EQ(d.object(0x1C32, 0x0B), 3u);           // SM-event missed (ETG.1020 order, L4742)
  EXPECT_EQ(d.object(0x1C33, 0x0B), 3u);
  EXPECT_EQ(d.object(0x1C32, 0x20), 0u);
}

// E-807 (L7119-L7123) names no threshold object; the profile's fixed threshold is 15 consecutive
// misses (docs/products.md errata). Before: threshold 0, E-807 never fired.
TEST(SyncModule, Ds5c1LostSync0IsE807After15Misses) {
  Drive d("ds5c1");
  d.sdo_write(0x1C32, 0x01, 2);
  d.sdo_write(0x1C33, 0x01, 2);
  d.sdo_write(0x1C32, 0x02, 1000000);
  d.program_sync0(1000000);
  ASSERT_TRUE(d.request_safeop().ok());
  d.enter(ecat::AlState::SafeOp, ecat::AlState::Op);
  d.run_until(d.now() + 40 * kMs);
  ASSERT_TRUE(d.module().locked());
  d.write(0x0981, {0x00});                        // the master stops SYNC0
  d.run_until(d.now() + 14 * kMs);                // 14 misses (due from 1.5 ms after the last pulse)
  EXPECT_TRUE(d.faults.empty());
  d.run_until(d.now() + 2 * kMs);
  ASSERT_EQ(d.faults.size(), 1u);
  EXPECT_EQ(d.faults[0].code, 0x002C);            // E-807 (L7119, L7123)
  EXPECT_EQ(d.faults[0].state, ecat::AlState::SafeOp);
  EXPECT_EQ(d.object(0x1C32, 0x20), 1u);          // Sync error (L5695)
}

TEST(SyncModule, Ds5c1CyclePhaseJumpSetsSyncErrorFlag) {
  Drive d("ds5c1");
  d.sdo_write(0x1C32, 0x01, 2);
  d.sdo_write(0x1C33, 0x01, 2);
  d.sdo_write(0x1C32, 0x02, 1000000);
  d.program_sync0(1000000);
  ASSERT_TRUE(d.request_safeop().ok());
  d.run_until(d.now() + 40 * kMs);
  ASSERT_TRUE(d.module().locked());
  EXPECT_EQ(d.object(0x1C32, 0x20), 0u);
  d.program_sync0(1000000, 0x03, 5 * kMs + 300000);   // restarted off the old grid
  d.run_until(d.now() + 5 * kMs + 500000);         // the first pulse of the new grid
  ASSERT_EQ(d.faults.size(), 1u);
  EXPECT_EQ(d.faults[0].code, 0x0032);             // E-806
  EXPECT_EQ(d.object(0x1C32, 0x20), 1u);           // 20h "Sync error" (L5695)
  EXPECT_EQ(d.object(0x1C32, 0x0C), 0u);           // counters "not supported" (L5687-L5694)
  // The drive locks onto the new grid again; the flag clears with the lock.
  d.run_until(d.now() + 10 * kMs);
  EXPECT_TRUE(d.module().locked());
  EXPECT_EQ(d.object(0x1C32, 0x20), 0u);
  EXPECT_EQ(d.faults.size(), 1u);
}

TEST(SyncModule, Sync0CycleChangedAfterLockIsPllError) {
  Drive d("ds5c1");
  d.sdo_write(0x1C32, 0x01, 2);
  d.sdo_write(0x1C33, 0x01, 2);
  d.sdo_write(0x1C32, 0x02, 1000000);
  d.program_sync0(1000000);
  ASSERT_TRUE(d.request_safeop().ok());
  d.run_until(d.now() + 40 * kMs);
  ASSERT_TRUE(d.module().locked());
  d.write(0x09A0, le(2000000, 4));                  // E-806: the SYNC0 period changes
  d.run_until(d.now() + 10 * kMs);
  ASSERT_FALSE(d.faults.empty());
  EXPECT_EQ(d.faults[0].code, 0x0032);
  EXPECT_EQ(d.faults[0].state, ecat::AlState::SafeOp);
}

// ---- other modes ------------------------------------------------------------------------------

TEST(SyncModule, FreeRunRunsOnTheLocalTimerAt1C32Cycle) {
  Drive d("a6b");
  d.sdo_write(0x1C32, 0x02, 2000000);
  ASSERT_TRUE(d.request_safeop().ok());     // 0981h = 0: free run
  EXPECT_EQ(d.module().mode(), SyncMode::FreeRun);
  EXPECT_EQ(d.started, std::vector<SyncMode>{SyncMode::FreeRun});
  EXPECT_EQ(d.object(0x1C32, 0x0A), 0u);
  const Nanos start = d.now();
  d.run_until(start + 100 * kMs);
  ASSERT_EQ(d.cycle_times.size(), 50u);
  EXPECT_EQ(d.cycle_times.front(), start + 2 * kMs);
  EXPECT_TRUE(d.faults.empty());
}

TEST(SyncModule, LeavingSafeOpStopsTheCycle) {
  Drive d("a6b");
  d.sdo_write(0x1C32, 0x02, 1000000);
  d.program_sync0(1000000);
  ASSERT_TRUE(d.request_safeop().ok());
  d.run_until(d.now() + 30 * kMs);
  const std::size_t cycles = d.cycle_times.size();
  EXPECT_GT(cycles, 0u);
  d.enter(ecat::AlState::SafeOp, ecat::AlState::PreOp);
  d.run_until(d.now() + 30 * kMs);
  EXPECT_EQ(d.cycle_times.size(), cycles);
  EXPECT_EQ(d.module().next_deadline(), std::numeric_limits<Nanos>::max());
}

}  // namespace
}  // namespace vdrive::firmware::sync
