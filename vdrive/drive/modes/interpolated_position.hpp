#pragma once
// Interpolated position (ip, 6060h = 7), DS1000A-EC only (manual 8.5, L2359-L2636):
//  * Records: 60C1h-01h (I32, user units). An SDO write appends one record; mapped to the RxPDO it
//    is written every bus cycle (on_cycle()) (L2515-L2527).
//  * Buffer 60C4h: 01h max 256 records, 02h buffer size in use, 03h organisation 0 FIFO / 1 ring,
//    04h buffer position (next free slot), 06h buffer clear: 0 = cleared and writes refused,
//    1 = writes enabled; the default 0 means the master opens it first (L2544-L2571, L5070-L5084).
//  * FIFO: writes at the tail, reads in order; motion ends when the read pointer catches the write
//    pointer, so continuous motion needs a record every cycle (L2582-L2592). Ring: writes at 04h,
//    reads slots 0..size-1 cyclically, indefinitely (L2598-L2606).
//  * Every 1 ms (fixed, 60C2h, L2533-L2535) the next record is taken and the demand moves
//    linearly to it (60C0h = 0 is the only sub-mode, L2509-L2513).
//  * 6040h bit 4 enables interpolation, bit 8 halts (605Dh). 6041h bit 10 target reached (halt 0:
//    the buffer ran out and the demand stands on the last record; halt 1: stopped), bit 12
//    interpolation active ("target position command valid"), bit 13 following error (L2440-L2470).
// Where the manual is silent (decisions of this model): 60C4h-02h = 0 means "all 256" for a FIFO
// and "as far as written" for a ring; a full FIFO refuses further records (SDO abort 08000020h);
// writes while the buffer is closed abort with 08000022h (device state); changing 03h clears.
#include <array>
#include <cstdint>
#include <memory>

#include "vdrive/drive/mode_handler.hpp"
#include "vdrive/drive/modes/cyclic_following_error.hpp"
#include "vdrive/drive/modes/cyclic_halt.hpp"
#include "vdrive/drive/motion_ramp.hpp"
#include "vdrive/od/sdo_abort.hpp"

namespace vdrive::drive {

// The 60C4h record buffer and its objects; shared between the mode and the SDO write hooks.
class InterpolationBuffer {
public:
  static constexpr std::size_t kMaxRecords = 256;  // 60C4h-01h (L2544-L2571)

  explicit InterpolationBuffer(od::ObjectStore& objects);

  // One record written (SDO or PDO). Ok, or why it was refused.
  od::SdoAbort write(std::int32_t record);
  // The next record in reading order; false when there is none (FIFO drained, ring empty).
  bool read(std::int32_t& record);
  void clear();
  // Applies 60C4h-06h (clear gate) and 03h (organisation) as they stand now; the PDO path changes
  // them without hooks.
  void sync_configuration();

  bool open() const { return gate_.get() == 1; }
  bool ring() const { return organisation_ == 1; }
  std::size_t count() const { return count_; }        // FIFO: records waiting

private:
  std::size_t fifo_capacity() const;
  std::size_t ring_length() const;

  ObjectRef<std::uint32_t> size_;            // 60C4h-02h
  ObjectRef<std::uint8_t> organisation_obj_; // 60C4h-03h
  ObjectRef<std::uint16_t> position_;        // 60C4h-04h
  ObjectRef<std::uint8_t> gate_;             // 60C4h-06h
  std::array<std::int32_t, kMaxRecords> records_{};
  std::uint8_t organisation_ = 0;
  std::size_t head_ = 0;     // FIFO: next to read; ring: next slot to read
  std::size_t count_ = 0;    // FIFO records waiting
  std::size_t written_ = 0;  // ring: slots written since the last clear (highest + 1)
};

class InterpolatedPositionMode final : public ModeHandler {
public:
  // Installs the 60C1h/60C4h SDO write hooks on ctx.objects (construction time).
  explicit InterpolatedPositionMode(const DriveContext& ctx);

  std::int8_t mode() const override { return mode::ip; }
  void activate(const AxisSample& s) override;
  Setpoint step(const AxisSample& s, std::uint16_t controlword) override;
  void idle(const AxisSample& s, std::uint16_t controlword) override;
  std::uint16_t status_bits() const override { return status_; }
  void on_cycle(Nanos now) override;
  void outputs_mapped(const MappedOutputs& outputs) override;

  const InterpolationBuffer& buffer() const { return *buffer_; }
  static constexpr Nanos kInterpolationPeriod = 1'000'000;  // L2363, L2533-L2535

private:
  void hold(double position);

  const DriveContext& ctx_;
  std::shared_ptr<InterpolationBuffer> buffer_;
  ObjectRef<std::int32_t> record_;  // 60C1h-01h
  CyclicHalt halt_;
  CyclicFollowingError following_error_;
  bool record_in_pdo_ = false;   // 60C1h-01h is in the RxPDO mapping in effect
  bool interpolating_ = false;   // a segment runs (bit 4 on, records flowing)
  double from_ = 0.0, to_ = 0.0; // current 1 ms segment
  Nanos into_ = 0;               // time into it
  double output_ = 0.0;
  MotionState halting_{};
  bool halted_ = false;
  std::uint16_t status_ = 0;
};

}  // namespace vdrive::drive
