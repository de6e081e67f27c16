#include "vdrive/drive/io/touch_probe.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "plant/plant.hpp"

namespace vdrive::drive {
namespace {

// 60B8h / 60B9h bits of channel 1; channel 2 is the same shifted by 8.
namespace fn {
constexpr std::uint16_t enable = 1u << 0, continuous = 1u << 1, rising = 1u << 4, falling = 1u << 5;
}
namespace st {
constexpr std::uint16_t enabled = 1u << 0, rising_stored = 1u << 1, falling_stored = 1u << 2;
}
constexpr unsigned kChannelShift = 8;
constexpr std::int32_t kToggleStoredBits = 1 << 13;  // A6B 3697h bit 13 (L25802)

// DS1000A-EC 60D0h values (L3757-L3789).
namespace source {
constexpr std::int16_t interlock = -4, org = -3, lm_plus = -2, lm_minus = -1, in1 = 1, in2 = 2,
                       encoder_zero = 6;
}

std::int32_t to_i32(double user) {
  const double r = std::round(user);
  return static_cast<std::int32_t>(std::clamp(r, double(std::numeric_limits<std::int32_t>::min()),
                                              double(std::numeric_limits<std::int32_t>::max())));
}

}  // namespace

TouchProbe::TouchProbe(const DriveContext& ctx)
    : ctx_(ctx), logic_(ctx), function_(ctx.objects, 0x60B8), status_ref_(ctx.objects, 0x60B9),
      mode_display_(ctx.objects, 0x6061) {
  od::ObjectStore& s = ctx.objects;
  for (int i = 0; i < 2; ++i) {
    const auto k = static_cast<std::uint16_t>(2 * i);
    ChannelObjects& o = objects_[i];
    o.rising_position = ObjectRef<std::int32_t>(s, 0x60BA + k);
    o.falling_position = ObjectRef<std::int32_t>(s, 0x60BB + k);
    o.rising_time = ObjectRef<std::uint32_t>(s, 0x60D1 + k);
    o.falling_time = ObjectRef<std::uint32_t>(s, 0x60D2 + k);
    o.rising_count = ObjectRef<std::uint16_t>(s, 0x60D5 + k);
    o.falling_count = ObjectRef<std::uint16_t>(s, 0x60D6 + k);
    o.source = ObjectRef<std::int16_t>(s, 0x60D0, static_cast<std::uint8_t>(i + 1), static_cast<std::int16_t>(i + 1));
  }
  if (logic_.product() == IoProduct::A6B) function_expansion_3_ = ObjectRef<std::int32_t>(s, 0x3697);
  power_on();
}

void TouchProbe::power_on() {
  channels_ = {};
  enable_seen_ = {};
  have_previous_ = false;
  pending_alarm_ = {};
  last_mode_ = mode_display_.get();
  write_status();
}

void TouchProbe::cancel_channels() {
  channels_ = {};
  // A channel runs again only after 60B8h bit 0/8 goes 0 -> 1 (L24732-L24736 with L25619-L25621).
  const std::uint16_t f = function_.get();
  for (int i = 0; i < 2; ++i) enable_seen_[i] = (f & (fn::enable << (kChannelShift * i))) != 0;
}

void TouchProbe::cancel() {
  cancel_channels();
  write_status();
}

std::string_view TouchProbe::pending_alarm() {
  const std::string_view alarm = pending_alarm_;
  pending_alarm_ = {};
  return alarm;
}

void TouchProbe::resolve_trigger(int index, unsigned select, Channel& ch) const {
  const std::uint32_t own_input = index == 0 ? plant::input::probe1 : plant::input::probe2;
  auto input = [&ch](std::uint32_t bit) { ch.trigger = Trigger::Input; ch.input_bit = bit; };
  ch.trigger = Trigger::None;
  switch (logic_.product()) {
    case IoProduct::A6B:
    case IoProduct::Generic:
      if (select == 0) input(own_input);                 // EXT1 / EXT2
      else ch.trigger = Trigger::Index;                  // Z phase
      break;
    case IoProduct::DS5C1:
      if (select == 0) input(own_input);                 // Z (select 1) not supported: never latches
      break;
    case IoProduct::DS1000A:
      if (select == 0) input(own_input);                 // IN1 / IN2
      else if (select == 1) ch.trigger = Trigger::Index;  // software encoder zero
      else if (select == 2) {
        switch (objects_[index].source.get()) {
          case source::interlock: input(din::torque_off); break;
          case source::org: input(plant::input::home); break;
          case source::lm_plus: input(plant::input::positive_limit); break;
          case source::lm_minus: input(plant::input::negative_limit); break;
          case source::in1: input(plant::input::probe1); break;
          case source::in2: input(plant::input::probe2); break;
          case source::encoder_zero: ch.trigger = Trigger::Index; break;
          default: break;  // IN3-IN7 are not wired in the plant; 5 (Z) unsupported; reserved values
        }
      }
      break;
  }
}

void TouchProbe::start(int index, std::uint16_t function) {
  const auto f = static_cast<std::uint16_t>(function >> (kChannelShift * index));
  Channel ch;
  ch.running = true;
  ch.continuous = (f & fn::continuous) != 0;
  ch.rising = (f & fn::rising) != 0;
  ch.falling = (f & fn::falling) != 0;
  const unsigned select = logic_.product() == IoProduct::DS1000A ? (f >> 2) & 0x3u : (f >> 2) & 0x1u;
  resolve_trigger(index, select, ch);

  // An index mark has no falling edge: DS1000A-EC latches software encoder zero on rising only
  // (L3532-L3534); the A6B asks not to pick falling with Z (L24726).
  if (ch.trigger == Trigger::Index) ch.falling = false;
  if (ch.rising && ch.falling && !ctx_.profile.touch_probe.both_edges_at_once) ch.falling = false;

  const bool external = ch.trigger == Trigger::Input && ch.input_bit == (index == 0 ? plant::input::probe1 : plant::input::probe2);
  if (external && !logic_.probe_assigned(index + 1)) {
    if (logic_.product() == IoProduct::A6B) pending_alarm_ = "88.3";     // L24704-L24706
    if (logic_.product() == IoProduct::DS5C1) pending_alarm_ = "E-883";  // L4554
    ch.running = false;
  }
  channels_[index] = ch;
}

void TouchProbe::latch(int index, bool rising_edge, double position, std::uint64_t time_ns) {
  Channel& ch = channels_[index];
  ChannelObjects& o = objects_[index];
  const bool toggle = (function_expansion_3_.get() & kToggleStoredBits) != 0;
  bool& stored = rising_edge ? ch.rising_stored : ch.falling_stored;
  stored = toggle ? !stored : true;
  (rising_edge ? ch.rising_done : ch.falling_done) = true;
  (rising_edge ? o.rising_position : o.falling_position).set(to_i32(position));
  (rising_edge ? o.rising_time : o.falling_time).set(static_cast<std::uint32_t>(time_ns));
  if (ch.continuous) {  // counters count continuous-mode latches only, wrapping after 65535
    ObjectRef<std::uint16_t>& count = rising_edge ? o.rising_count : o.falling_count;
    count.set(static_cast<std::uint16_t>(count.get() + 1u));
  }
}

void TouchProbe::step(std::uint32_t inputs_before, std::uint32_t inputs_now, const AxisSample& s,
                      std::uint64_t system_time_ns) {
  const std::int8_t mode = mode_display_.get();
  const bool in_hm = mode == mode::hm;
  if (mode != last_mode_) {
    // Switching to hm cancels (A6B L24736, DS5C1 L4564); the DS5C1 needs a new start after any
    // mode change (L4672).
    if (in_hm || logic_.product() == IoProduct::DS5C1) cancel_channels();
    last_mode_ = mode;
  }

  const std::uint16_t function = function_.get();
  for (int i = 0; i < 2; ++i) {
    const bool enable = (function & (fn::enable << (kChannelShift * i))) != 0;
    if (!enable) channels_[i] = Channel{};
    else if (!enable_seen_[i] && !(in_hm && logic_.product() == IoProduct::DS5C1)) start(i, function);
    enable_seen_[i] = enable;
  }

  const bool running = channels_[0].running || channels_[1].running;
  const std::uint32_t before = running ? logic_.detected(inputs_before) : 0;  // idle: not needed
  const std::uint32_t now = running ? logic_.detected(inputs_now) : 0;
  const double start_position = have_previous_ ? previous_position_ : s.position;
  const std::uint64_t start_time = have_previous_ ? previous_time_ns_ : system_time_ns;
  const double mid_position = 0.5 * (start_position + s.position);
  // The DC times are the low 32 bits of the system time (60BAh-60BDh are 32 bits): the step's
  // length survives their wrap-around every 4.3 s.
  const std::uint64_t elapsed = static_cast<std::uint32_t>(system_time_ns - start_time);
  const std::uint64_t mid_time = start_time + elapsed / 2;

  for (int i = 0; i < 2; ++i) {
    Channel& ch = channels_[i];
    if (!ch.running) continue;
    bool rose = false, fell = false;
    double position = mid_position;
    std::uint64_t time = mid_time;
    if (ch.trigger == Trigger::Input) {
      rose = !(before & ch.input_bit) && (now & ch.input_bit);
      fell = (before & ch.input_bit) && !(now & ch.input_bit);
    } else if (ch.trigger == Trigger::Index && s.index_passed) {
      rose = true;
      position = s.index_position;
      const double travel = s.position - start_position;
      const double fraction = travel != 0.0 ? std::clamp((s.index_position - start_position) / travel, 0.0, 1.0) : 1.0;
      time = start_time + static_cast<std::uint64_t>(fraction * double(elapsed));
    }
    if (rose && ch.rising && (ch.continuous || !ch.rising_done)) latch(i, true, position, time);
    if (fell && ch.falling && (ch.continuous || !ch.falling_done)) latch(i, false, position, time);
  }

  have_previous_ = true;
  previous_position_ = s.position;
  previous_time_ns_ = system_time_ns;
  write_status();
}

void TouchProbe::write_status() {
  std::uint16_t v = 0;
  for (int i = 0; i < 2; ++i) {
    const Channel& ch = channels_[i];
    std::uint16_t bits = 0;
    if (ch.running) bits |= st::enabled;
    if (ch.rising_stored) bits |= st::rising_stored;
    if (ch.falling_stored) bits |= st::falling_stored;
    v |= static_cast<std::uint16_t>(bits << (kChannelShift * i));
  }
  status_ = v;
  status_ref_.set(v);
}

}  // namespace vdrive::drive
