#pragma once
// Process data: PDO mapping and assignment rules, the PreOp->SafeOp checks of the mapping and of
// SM2/SM3, the cyclic copy between the SM2/SM3 3-buffers and the mapped objects, and the SM2
// (process-data) watchdog. See docs/process-data.md.
//
// Who calls what, when:
//  - Free run and SM2-event mode (1C32h-01h = 0/1, DC off): this module runs the cycle itself.
//    On the SM2 event (AL event bit 10, the master wrote outputs) it calls exchange_outputs() and
//    then produce_inputs(); on the SM3 event (bit 11, the master read the inputs) it calls
//    produce_inputs() so the next read finds fresh inputs.
//  - DC mode: the sync module calls set_cycle_by_sync(true) when it takes over (at PS) and then
//    exchange_outputs() on SYNC0 and produce_inputs() at SYNC0 + input shift. The SM2/SM3
//    events then only release the buffers (outputs reach the objects at SYNC0; the inputs
//    latched at the last produce_inputs() are handed out again). A SYNC0 with no outputs written
//    since the last one does not call `after_outputs` (a lost set-point, not a repeated one).
// Outputs reach the objects only in Op; inputs are produced in SafeOp and Op.
//
// Cyclic path (events, exchange_outputs, produce_inputs): a precompiled CopyPlan over fixed
// buffers; no allocation, no locks. Construction allocates (write hooks).
#include <array>
#include <cstdint>
#include <functional>
#include <utility>

#include "vdrive/firmware/firmware_module.hpp"
#include "vdrive/firmware/pdi.hpp"
#include "vdrive/firmware/pdo/copy_plan.hpp"
#include "vdrive/firmware/pdo/pdo_limits.hpp"
#include "vdrive/firmware/pdo/pdo_mapping.hpp"
#include "vdrive/profile/product_profile.hpp"

namespace vdrive::firmware::pdo {

class ProcessDataModule final : public FirmwareModule {
public:
  explicit ProcessDataModule(FirmwareContext& context);

  // The store was reset to defaults (the dictionary carries the factory PDO configuration, see
  // od/default_pdo_objects.hpp) and stored parameters loaded: no mapping in effect until the next
  // PreOp->SafeOp.
  void power_on(Nanos now) override;
  std::uint32_t serviced_events() const override;
  void on_events(std::uint32_t events, Nanos now) override;
  CheckResult check_transition(ecat::AlState from, ecat::AlState to) override;
  void entered(ecat::AlState from, ecat::AlState to, Nanos now) override;
  void tick(Nanos now) override;
  Nanos next_deadline() const override;

  // Reads the whole SM2 buffer (releasing it) and, in Op, scatters it into the RxPDO objects.
  void exchange_outputs(Nanos now);
  // Gathers the TxPDO objects and writes the whole SM3 buffer (SafeOp and Op).
  void produce_inputs(Nanos now);
  // True while the sync module runs the cycle on SYNC0 (DC mode).
  void set_cycle_by_sync(bool by_sync) { cycle_by_sync_ = by_sync; }
  // The application around the process data (the CiA402 drive): `after_outputs` runs when new
  // outputs reached the RxPDO objects (Op), `before_inputs` just before the TxPDO objects are
  // gathered, so the inputs carry the drive's state at that instant. Construction time only.
  void set_application(std::function<void(Nanos)> after_outputs, std::function<void(Nanos)> before_inputs) {
    after_outputs_ = std::move(after_outputs);
    before_inputs_ = std::move(before_inputs);
  }

  // Told the RxPDO mapping each time one becomes effective (PreOp->SafeOp), so the application
  // learns which objects arrive cyclically without reading the mapping objects. Construction time only.
  void on_outputs_mapped(std::function<void(const ResolvedMapping&)> listener) {
    outputs_mapped_ = std::move(listener);
  }

  bool running() const { return running_; }                // SafeOp or Op with a valid mapping
  bool outputs_valid() const { return outputs_valid_; }    // Op and outputs received since
  std::uint16_t output_bytes() const { return rx_plan_.bytes(); }
  std::uint16_t input_bytes() const { return tx_plan_.bytes(); }
  const PdoLimits& limits() const { return limits_; }

private:
  CheckResult check_preop_to_safeop();
  void check_sms_while_running();
  void on_watchdog();
  void read_outputs();
  void write_inputs();
  std::uint16_t code_or(std::uint16_t code, std::uint16_t etg) const { return code ? code : etg; }

  FirmwareContext& ctx_;
  PdoLimits limits_;
  WatchdogLimits watchdog_limits_;
  profile::AlStatusCodes codes_;
  std::uint32_t ram_end_;
  ResolvedMapping rx_map_, tx_map_;   // results of the last PS check
  CopyPlan rx_plan_, tx_plan_;
  std::array<std::uint8_t, kMaxPdoBytes> rx_image_{};
  std::array<std::uint8_t, kMaxPdoBytes> tx_image_{};
  std::array<SmChannel, kMaxSyncManagers> sms_{};
  int sm_count_;
  int outputs_sm_, inputs_sm_;                    // SM2/SM3, or the SMs an I/O device uses for them
  std::uint32_t outputs_event_, inputs_event_;    // their AL event bits
  bool mode_checked_;                             // SM2/SM3 control mode bits checked (pdo_rules)
  bool unused_disabled_;                          // an SM2/SM3 with nothing mapped must be disabled (pdo_rules)
  static constexpr Nanos kPollPeriod = 100'000;   // buffers without AL events are looked at this often
  bool polling_ = false;
  Nanos poll_at_ = 0;
  std::uint16_t sm2_start_ = 0, sm3_start_ = 0;
  bool running_ = false;
  bool outputs_valid_ = false;
  bool cycle_by_sync_ = false;
  bool new_outputs_ = false;   // DC mode: the master wrote SM2 since the last SYNC0
  std::function<void(Nanos)> after_outputs_, before_inputs_;
  std::function<void(const ResolvedMapping&)> outputs_mapped_;
};

}  // namespace vdrive::firmware::pdo
