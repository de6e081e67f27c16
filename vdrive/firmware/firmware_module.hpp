#pragma once
// A part of the slave firmware (mailbox + CoE, process data, sync, later CiA402) that plugs into
// SlaveFirmware. Each module says which AL events it services, may veto upward transitions with
// the product's AL status code, learns of state changes, and may run timed work. SlaveFirmware
// calls the modules in the order they were added; none of these calls may allocate.
#include <cstdint>
#include <limits>

#include "common/clock.hpp"
#include "ethercat/al_state.hpp"
#include "vdrive/firmware/al_state_machine.hpp"
#include "vdrive/firmware/sdo_abort_record.hpp"

namespace vdrive::od { class ObjectStore; }
namespace vdrive::profile { struct ProductProfile; }

namespace vdrive::firmware {

class Pdi;

// What every module may use. Lives as long as the SlaveFirmware.
struct FirmwareContext {
  const profile::ProductProfile& profile;
  Pdi& pdi;
  od::ObjectStore& objects;
  const AlStateMachine& esm;          // current state; modules never change it directly
  SdoAbortRecord* sdo_aborts = nullptr;  // the SDO server counts its aborts here (may be null)
};

class FirmwareModule {
public:
  virtual ~FirmwareModule() = default;

  // AL event request bits (0x0220) this module services; they are unmasked in 0x0204.
  virtual std::uint32_t serviced_events() const { return 0; }
  // Called from the PDI IRQ with the event bits that were pending (all of them; pick yours).
  virtual void on_events(std::uint32_t /*events*/, Nanos /*now*/) {}

  // Checks before an upward transition; the first failing module's result is reported.
  virtual CheckResult check_transition(ecat::AlState /*from*/, ecat::AlState /*to*/) { return CheckResult::pass(); }
  virtual void entered(ecat::AlState /*from*/, ecat::AlState /*to*/, Nanos /*now*/) {}

  // Control power on: the store was just reset to defaults; load what the drive keeps in
  // non-volatile memory (stored parameters) and forget RAM state.
  virtual void power_on(Nanos /*now*/) {}

  virtual void tick(Nanos /*now*/) {}
  virtual Nanos next_deadline() const { return std::numeric_limits<Nanos>::max(); }

  // A module that detects a failure on its own (watchdog, lost sync) sets a request here; the
  // firmware applies it (AL state fallback + code) after the call that set it.
  struct Fault {
    std::uint16_t code = 0;
    ecat::AlState state = ecat::AlState::Init;
  };
  bool take_fault(Fault& out) {
    if (fault_.code == 0) return false;
    out = fault_;
    fault_ = {};
    return true;
  }

protected:
  void raise_fault(std::uint16_t code, ecat::AlState state) { fault_ = {code, state}; }

private:
  Fault fault_;
};

}  // namespace vdrive::firmware
