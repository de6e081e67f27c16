#pragma once
// One slave (real profile, real ESC) driven as a master drives it for process data: SyncManagers
// and FMMUs written by hand over the wire (APWR), AL Control requests, LRW frames over the FMMUs.
// PdoBench runs the whole SlaveFirmware; ModuleBench runs the ProcessDataModule alone with its
// own ESM so a test can see the object values. Shared by the pdo_*_test.cpp files.
#include <gtest/gtest.h>

#include <array>
#include <memory>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "common/clock.hpp"
#include "esc_model/esc.hpp"
#include "vdrive/firmware/al_state_machine.hpp"
#include "vdrive/firmware/pdi.hpp"
#include "vdrive/firmware/pdo/process_data_module.hpp"
#include "vdrive/firmware/slave_firmware.hpp"
#include "vdrive/od/dictionary_cache.hpp"
#include "vdrive/od/object_store.hpp"
#include "vdrive/profile/profile_loader.hpp"
#include "vdrive/profile/sii_image.hpp"

namespace vdrive::test {

inline constexpr std::uint8_t kAprd = 0x01, kApwr = 0x02, kLrw = 0x0C;
inline constexpr std::uint32_t kLogicalOutputs = 0x00010000;

class WireBench {
public:
  explicit WireBench(const std::string& id)
      : product(profile::load_profile(id)), esc(profile::make_esc_config(product), clock) {}
  virtual ~WireBench() = default;

  // What the event loop does after a frame or a tick: service the firmware's IRQ.
  virtual void service() = 0;
  // Time passes: the ESC runs its timers (watchdogs), then the firmware is serviced.
  void advance(Nanos dt) {
    clock.advance(dt);
    esc.tick(clock.now());
    service();
  }

  // A frame with one datagram; `address` is ADP|ADO<<16 for physical commands, the logical
  // address for LRW.
  static std::vector<std::uint8_t> frame(std::uint8_t cmd, std::uint32_t address, std::size_t size) {
    const std::size_t dg_len = 10 + size + 2;
    std::vector<std::uint8_t> pdu = {static_cast<std::uint8_t>(dg_len & 0xFF),
                                     static_cast<std::uint8_t>(0x10 | ((dg_len >> 8) & 0x07)),
                                     cmd, 0x00,
                                     static_cast<std::uint8_t>(address),
                                     static_cast<std::uint8_t>(address >> 8),
                                     static_cast<std::uint8_t>(address >> 16),
                                     static_cast<std::uint8_t>(address >> 24),
                                     static_cast<std::uint8_t>(size & 0xFF),
                                     static_cast<std::uint8_t>((size >> 8) & 0x07), 0x00, 0x00};
    pdu.resize(12 + size + 2, 0);
    return pdu;
  }
  static std::span<std::uint8_t> data_of(std::vector<std::uint8_t>& pdu) {
    return std::span<std::uint8_t>(pdu).subspan(12, pdu.size() - 14);
  }
  static std::uint16_t wkc_of(const std::vector<std::uint8_t>& pdu) {
    return static_cast<std::uint16_t>(pdu[pdu.size() - 2] | (pdu[pdu.size() - 1] << 8));
  }

  // Runs a prepared frame (no allocation) and services the PDI IRQ as the event loop does.
  std::uint16_t run(std::vector<std::uint8_t>& pdu) {
    pdu[pdu.size() - 2] = 0;
    pdu[pdu.size() - 1] = 0;
    esc.process_frame(pdu, esc::FrameTiming{clock.now()});
    service();
    return wkc_of(pdu);
  }

  void write(std::uint16_t ado, const std::vector<std::uint8_t>& bytes) {
    std::vector<std::uint8_t> pdu = frame(kApwr, static_cast<std::uint32_t>(ado) << 16, bytes.size());
    std::copy(bytes.begin(), bytes.end(), data_of(pdu).begin());
    EXPECT_EQ(run(pdu), 1) << "APWR 0x" << std::hex << ado;
  }
  void write_u16(std::uint16_t ado, std::uint16_t v) {
    write(ado, {static_cast<std::uint8_t>(v), static_cast<std::uint8_t>(v >> 8)});
  }
  std::uint16_t read_u16(std::uint16_t ado) {
    std::vector<std::uint8_t> pdu = frame(kAprd, static_cast<std::uint32_t>(ado) << 16, 2);
    EXPECT_EQ(run(pdu), 1) << "APRD 0x" << std::hex << ado;
    return static_cast<std::uint16_t>(pdu[12] | (pdu[13] << 8));
  }

  void sm(int n, std::uint16_t start, std::uint16_t length, std::uint8_t control, bool enable) {
    const auto at = static_cast<std::uint16_t>(0x0800 + 8 * n);
    write(static_cast<std::uint16_t>(at + 6), {0x00});  // disable first: config is locked while enabled
    write(at, {static_cast<std::uint8_t>(start), static_cast<std::uint8_t>(start >> 8),
               static_cast<std::uint8_t>(length), static_cast<std::uint8_t>(length >> 8), control});
    write(static_cast<std::uint16_t>(at + 6), {static_cast<std::uint8_t>(enable ? 1 : 0)});
  }
  void fmmu(int n, std::uint32_t logical, std::uint16_t length, std::uint16_t physical,
            std::uint8_t type) {
    write(static_cast<std::uint16_t>(0x0600 + 16 * n),
          {static_cast<std::uint8_t>(logical), static_cast<std::uint8_t>(logical >> 8),
           static_cast<std::uint8_t>(logical >> 16), static_cast<std::uint8_t>(logical >> 24),
           static_cast<std::uint8_t>(length), static_cast<std::uint8_t>(length >> 8), 0x00, 0x07,
           static_cast<std::uint8_t>(physical), static_cast<std::uint8_t>(physical >> 8), 0x00, type,
           0x01, 0x00, 0x00, 0x00});
  }

  std::uint16_t al_status() { return read_u16(0x0130); }
  std::uint16_t al_code() { return read_u16(0x0134); }
  void request(std::uint16_t control) { write_u16(0x0120, control); }

  // Mailbox SyncManagers as the product's SII declares them.
  void mailbox_layout() {
    for (int n = 0; n < 2; ++n) {
      const profile::SyncManagerSpec& s = product.sync_managers[static_cast<std::size_t>(n)];
      sm(n, s.start, s.length, s.control, true);
    }
  }

  // SM2/SM3 at the SII's addresses with the given lengths, FMMU0 (outputs) and FMMU1 (inputs)
  // back to back from kLogicalOutputs.
  void process_data_layout(std::uint16_t out_bytes, std::uint16_t in_bytes) {
    const profile::SyncManagerSpec& s2 = product.sync_managers[2];
    const profile::SyncManagerSpec& s3 = product.sync_managers[3];
    sm(2, s2.start, out_bytes, s2.control, out_bytes > 0);
    sm(3, s3.start, in_bytes, s3.control, in_bytes > 0);
    if (out_bytes > 0) fmmu(0, kLogicalOutputs, out_bytes, s2.start, 0x02);
    if (in_bytes > 0) fmmu(1, kLogicalOutputs + out_bytes, in_bytes, s3.start, 0x01);
  }

  VirtualClock clock;
  profile::ProductProfile product;
  esc::Esc esc;
};

// The whole firmware, as in the product.
class PdoBench : public WireBench {
public:
  explicit PdoBench(const std::string& id) : WireBench(id), fw(product, esc) {
    fw.power_on(clock.now());
  }
  void service() override {
    if (esc.pdi_irq() != 0) fw.on_irq(clock.now());
  }
  firmware::SlaveFirmware fw;
};

// The process-data module alone, with a state machine whose other checks pass; AL Control is
// given to the ESM directly and the AL events are read as the firmware reads them.
class ModuleBench : public WireBench, public firmware::TransitionHooks {
public:
  explicit ModuleBench(const std::string& id)
      : WireBench(id),
        dictionary(od::shared_dictionary(product)),
        objects(*dictionary),
        pdi(esc),
        esm(firmware::EsmTraits::of(product)),
        context{product, pdi, objects, esm},
        module(context) {
    esm.reset();
  }

  void service() override {
    const std::uint32_t events = pdi.read_u32(ecat::reg::kAlEventRequest);
    module.on_events(events, clock.now());
    firmware::FirmwareModule::Fault fault;
    if (module.take_fault(fault)) esm.raise(fault.state, fault.code, *this);
    if (events & ecat::reg::al_event::kSmActivation) {
      for (int n = 0; n < 4; ++n) pdi.read_sm(n);  // as the firmware does: clears the event
    }
  }
  void go(std::uint16_t control) {
    esm.on_al_control(ecat::AlControl::decode(control), 0, *this);
  }
  std::span<std::uint8_t> value(std::uint16_t index, std::uint8_t subindex) {
    const od::EntryDesc* e = dictionary->find(index, subindex);
    EXPECT_NE(e, nullptr) << std::hex << index << ":" << int{subindex};
    return objects.raw(*e);
  }

  firmware::CheckResult check_init_to_preop() override { return firmware::CheckResult::pass(); }
  firmware::CheckResult check_init_to_boot() override { return firmware::CheckResult::pass(); }
  firmware::CheckResult check_preop_to_safeop() override {
    return module.check_transition(ecat::AlState::PreOp, ecat::AlState::SafeOp);
  }
  firmware::CheckResult check_safeop_to_op() override {
    return module.check_transition(ecat::AlState::SafeOp, ecat::AlState::Op);
  }
  void entered(ecat::AlState from, ecat::AlState to) override {
    module.entered(from, to, clock.now());
  }

  std::shared_ptr<const od::Dictionary> dictionary;
  od::ObjectStore objects;
  firmware::Pdi pdi;
  firmware::AlStateMachine esm;
  firmware::FirmwareContext context;
  firmware::pdo::ProcessDataModule module;
};

}  // namespace vdrive::test
