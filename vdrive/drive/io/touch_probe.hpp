#pragma once
// Touch probe 60B8h/60B9h: latches the position (60BAh-60BDh, user units) on
// edges of a trigger signal, per channel 1/2, as each product documents it:
//  - 60B8h bits 1-7 / 9-15 are taken over on the 0->1 edge of bit 0 / bit 8 and ignored while the
//    channel runs (A6B L25619-L25621, DS5C1 L4668-L4672); bit 1/9 first event (one latch per
//    edge kind, L25638-L25644) or continuous (every edge, L25794-L25800); bits 4/5, 12/13 rising
//    and falling. Where profile.touch_probe.both_edges_at_once is false (DS5C1 L4566) a channel
//    set for both arms the rising edge only: the manual leaves that combination undefined.
//  - Trigger select: A6B bit 2/10 EXT1/EXT2 or Z (L25158-L25260; no falling edge on Z, L24726);
//    DS5C1 external input only, Z "not supported" (L10056-L10078: the channel runs but never
//    latches); DS1000A-EC bits 3-2/11-10: 00 IN1/IN2, 01 software encoder zero (rising only,
//    L3532-L3534), 10 the signal 60D0h-01h/02h names (L3757-L3789; 5 "Z" is not supported), 11
//    reserved (never latches).
//  - DS1000A-EC: time stamps 60D1h-60D4h (ns, low 32 bits of DC system time) on every latch, edge
//    counters 60D5h-60D8h in continuous mode only, wrapping after 65535 (L3793-L3842).
//  - A6B 3697h bit 13: the stored bits of 60B9h toggle on each latch (L25802).
//  - Cancelled (60B9h = 0; a new 0->1 edge is needed) on ESM Init (cancel()) and on switching to
//    hm (A6B L24732-L24736, DS5C1 L4560-L4564); the DS5C1 has no probe in hm (L4516) and needs the
//    0->1 edge again after any mode change (L4672).
//  - Starting a channel whose external input has no terminal raises A6B Err88.3 (L24704-L24706) /
//    DS5C1 E-883 (L4554) and the channel does not run.
// Edge positions: an input edge happened somewhere in the step, so it is latched at the midpoint
// of the step's start and end positions (time stamp likewise); an index crossing is latched at
// AxisSample::index_position exactly, its time interpolated from it. Allocates nothing per step.
#include <array>
#include <cstdint>
#include <string_view>

#include "vdrive/drive/drive_context.hpp"
#include "vdrive/drive/drive_types.hpp"
#include "vdrive/drive/io/input_logic.hpp"
#include "vdrive/drive/object_ref.hpp"

namespace vdrive::drive {

class TouchProbe {
public:
  explicit TouchProbe(const DriveContext& ctx);

  void power_on();  // all channels off, 60B9h = 0
  void cancel();    // ESM Init: channels off, 60B9h = 0 until 60B8h bit 0/8 goes 0 -> 1 again

  // One control step. `inputs_before` / `inputs_now`: plant::input bits at the start and end of the
  // step, | din::torque_off while the TO input is open (DS1000A-EC 60D0h = -4); the product's
  // input logic is applied here. `s`: position (user) at the end of the step and the index
  // crossing; `system_time_ns`: DC system time at the end of the step. Reads 60B8h, 60D0h and
  // 6061h; writes 60B9h-60BDh and, where present, 60D1h-60D8h.
  void step(std::uint32_t inputs_before, std::uint32_t inputs_now, const AxisSample& s,
            std::uint64_t system_time_ns);

  // The vendor alarm a channel start raised ("88.3" / "E-883"), once; "" otherwise.
  std::string_view pending_alarm();

  std::uint16_t status() const { return status_; }  // 60B9h as last written

private:
  enum class Trigger : std::uint8_t { None, Input, Index };

  struct Channel {
    bool running = false;
    bool continuous = false;
    bool rising = false, falling = false;
    bool rising_done = false, falling_done = false;  // first-event mode: that edge was latched
    bool rising_stored = false, falling_stored = false;  // 60B9h bits 1/2 (9/10)
    Trigger trigger = Trigger::None;
    std::uint32_t input_bit = 0;                     // detected-input bit for Trigger::Input
  };

  struct ChannelObjects {
    ObjectRef<std::int32_t> rising_position, falling_position;      // 60BAh/60BBh, 60BCh/60BDh
    ObjectRef<std::uint32_t> rising_time, falling_time;             // 60D1h/60D2h, 60D3h/60D4h
    ObjectRef<std::uint16_t> rising_count, falling_count;           // 60D5h/60D6h, 60D7h/60D8h
    ObjectRef<std::int16_t> source;                                 // 60D0h-01h/02h
  };

  void start(int index, std::uint16_t function);
  void cancel_channels();
  void resolve_trigger(int index, unsigned select, Channel& ch) const;
  void latch(int index, bool rising_edge, double position, std::uint64_t time_ns);
  void write_status();

  const DriveContext& ctx_;
  InputLogic logic_;
  ObjectRef<std::uint16_t> function_, status_ref_;
  ObjectRef<std::int8_t> mode_display_;
  ObjectRef<std::int32_t> function_expansion_3_;   // A6B 3697h
  std::array<ChannelObjects, 2> objects_;
  std::array<Channel, 2> channels_{};
  std::array<bool, 2> enable_seen_{};              // 60B8h bit 0/8 at the previous step
  std::int8_t last_mode_ = 0;
  bool have_previous_ = false;
  double previous_position_ = 0.0;
  std::uint64_t previous_time_ns_ = 0;
  std::uint16_t status_ = 0;
  std::string_view pending_alarm_;
};

}  // namespace vdrive::drive
