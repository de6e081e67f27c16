#include "vdrive/drive/mode_selector.hpp"

#include <algorithm>

namespace vdrive::drive {

ModeSelector::ModeSelector(const DriveContext& ctx)
    : ctx_(ctx), requested_(ctx.objects, 0x6060), display_(ctx.objects, 0x6061) {}

bool ModeSelector::supported(std::int8_t mode) const {
  const auto& modes = ctx_.profile.modes.modes;
  return std::find(modes.begin(), modes.end(), mode) != modes.end();
}

void ModeSelector::power_on() {
  active_ = ctx_.profile.modes.default_mode;
  if (!supported(active_)) active_ = 0;
  target_ = active_;
  pending_ = false;
  changed_ = false;
  invalid_ = false;
  display_.set(active_);
}

void ModeSelector::step(Nanos now, bool enabled) {
  changed_ = false;
  const auto& spec = ctx_.profile.drive;
  const std::int8_t requested = requested_.get();
  invalid_ = requested != 0 && !supported(requested);

  std::int8_t wanted = target_;
  if (requested == 0) {
    if (!spec.zero_mode_keeps_previous) wanted = 0;
  } else if (!invalid_) {
    wanted = requested;
  }

  if (wanted != target_ && !pending_) {
    bool allowed = !enabled || spec.mode_switch_while_enabled;
    if (enabled)
      for (const auto& [from, to] : spec.forbidden_mode_switches)
        if (from == active_ && to == wanted) allowed = false;
    if (allowed) {
      target_ = wanted;
      pending_ = true;
      switch_done_ = now + static_cast<Nanos>(enabled ? spec.mode_switch_ns : 0);
    }
  }
  if (pending_ && now >= switch_done_) {
    pending_ = false;
    changed_ = active_ != target_;
    active_ = target_;
  }
  display_.set(active_);
}

}  // namespace vdrive::drive
