#include "vdrive/firmware/drive/drive_module.hpp"

#include <limits>

#include "ethercat/registers.hpp"
#include "vdrive/firmware/pdi.hpp"

namespace vdrive::firmware::drive_module {
DriveModule::DriveModule(FirmwareContext& context, const plant::PlantDescription& plant,
                         std::function<void(const ecat::coe::Emergency&)> emergency)
    : context_(context), plant_(plant) {
  engine_ = std::make_unique<vdrive::drive::DriveEngine>(context.profile, context.objects, plant_, 0,
                                                         plant.axes.at(0), std::move(emergency));
}

DriveModule::~DriveModule() = default;

vdrive::drive::BusState DriveModule::bus() const {
  vdrive::drive::BusState b;
  const ecat::AlState state = context_.esm.state();
  b.esm_init = state == ecat::AlState::Init;
  b.remote = rank(state) >= rank(ecat::AlState::PreOp) && state != ecat::AlState::Boot;
  b.al_error_pending = context_.esm.error();
  b.system_time_ns = context_.pdi.read_u32(reg::kDcSystemTime);  // low 32 bits of the local copy
  return b;
}

void DriveModule::power_on(Nanos now) {
  al_error_seen_ = 0;
  engine_->power_on(now);
}

bool DriveModule::raise_al_error(Nanos now) {
  const std::uint16_t code = context_.esm.error() ? context_.esm.error_code() : 0;
  if (code == al_error_seen_) return false;
  al_error_seen_ = code;
  return code != 0 && engine_->raise_al_error(code, now);
}

// The bus state costs a PDI read of the DC system time: taken only when a control step is due
// (advance_to does nothing otherwise).
void DriveModule::catch_up(Nanos now) {
  if (engine_->next_step() <= now) engine_->advance_to(now, bus());
}

bool DriveModule::step_once(Nanos now) {
  raise_al_error(now);
  return engine_->next_step() <= now && engine_->advance_one(now, bus());
}

void DriveModule::entered(ecat::AlState from, ecat::AlState to, Nanos now) {
  catch_up(now);
  const bool by_error = raise_al_error(now);
  engine_->esm_changed(from, to, now, by_error);
}

void DriveModule::tick(Nanos now) {
  raise_al_error(now);
  catch_up(now);
}

Nanos DriveModule::next_deadline() const {
  const Nanos step = engine_->next_step();
  return step > std::numeric_limits<Nanos>::max() - step_batch_ ? std::numeric_limits<Nanos>::max() : step + step_batch_;
}

void DriveModule::after_outputs(Nanos now) {
  catch_up(now);
  engine_->outputs_taken(now);
}

void DriveModule::before_inputs(Nanos now) { catch_up(now); }

static_assert(vdrive::drive::MappedOutputs::kCapacity >= pdo::kMaxMappedEntries,
              "the drive must hear of every entry an RxPDO can map");

void DriveModule::outputs_mapped(const pdo::ResolvedMapping& rx) {
  mapped_.clear();
  for (int i = 0; i < rx.count; ++i) {
    const od::EntryDesc* e = rx.items[static_cast<std::size_t>(i)].entry;
    if (e) mapped_.add(e->index, e->subindex);
  }
  engine_->outputs_mapped(mapped_);
}

}  // namespace vdrive::firmware::drive_module
