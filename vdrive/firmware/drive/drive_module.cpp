#include "vdrive/firmware/drive/drive_module.hpp"

#include "esc_model/registers.hpp"
#include "vdrive/firmware/pdi.hpp"

namespace vdrive::firmware::drive_module {
namespace {
constexpr std::uint16_t kDcSystemTime = 0x0910;  // local copy of the system time, low 32 bits
}  // namespace

DriveModule::DriveModule(FirmwareContext& context, const plant::PlantDescription& plant,
                         std::function<void(const coe::Emergency&)> emergency)
    : context_(context), plant_(plant) {
  engine_ = std::make_unique<vdrive::drive::DriveEngine>(context.profile, context.objects, plant_, 0,
                                                         plant.axes.at(0), std::move(emergency));
}

DriveModule::~DriveModule() = default;

vdrive::drive::BusState DriveModule::bus() const {
  vdrive::drive::BusState b;
  const AlState state = context_.esm.state();
  b.esm_init = state == AlState::Init;
  b.remote = rank(state) >= rank(AlState::PreOp) && state != AlState::Boot;
  b.al_error_pending = context_.esm.error();
  b.system_time_ns = context_.pdi.read_u32(kDcSystemTime);
  return b;
}

void DriveModule::power_on(Nanos now) { engine_->power_on(now); }

void DriveModule::entered(AlState from, AlState to, Nanos now) {
  engine_->advance_to(now, bus());
  engine_->esm_changed(from, to, now);
}

void DriveModule::tick(Nanos now) { engine_->advance_to(now, bus()); }

Nanos DriveModule::next_deadline() const { return engine_->next_step(); }

void DriveModule::after_outputs(Nanos now) {
  engine_->advance_to(now, bus());
  engine_->outputs_taken(now);
}

void DriveModule::before_inputs(Nanos now) { engine_->advance_to(now, bus()); }

}  // namespace vdrive::firmware::drive_module
