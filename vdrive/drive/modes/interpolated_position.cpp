#include "vdrive/drive/modes/interpolated_position.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <span>

#include "vdrive/firmware/pdo/pdo_mapping.hpp"

namespace vdrive::drive {

// --- InterpolationBuffer -------------------------------------------------------------------------

InterpolationBuffer::InterpolationBuffer(od::ObjectStore& o)
    : size_(o, 0x60C4, 2), organisation_obj_(o, 0x60C4, 3), position_(o, 0x60C4, 4), gate_(o, 0x60C4, 6) {
  organisation_ = organisation_obj_.get();
}

std::size_t InterpolationBuffer::fifo_capacity() const {
  const std::uint32_t size = size_.get();
  return size >= 1 && size <= kMaxRecords ? size : kMaxRecords;
}

std::size_t InterpolationBuffer::ring_length() const {
  const std::uint32_t size = size_.get();
  return size >= 1 && size <= kMaxRecords ? size : written_;
}

void InterpolationBuffer::clear() {
  head_ = count_ = written_ = 0;
  position_.set(0);
}

void InterpolationBuffer::sync_configuration() {
  const std::uint8_t organisation = organisation_obj_.get();
  if (organisation != organisation_) {
    organisation_ = organisation;
    clear();
  }
  // 60C4h-06h = 0: "buffer clear, access forbidden" (L2563-L2566).
  if (!open() && (head_ != 0 || count_ != 0 || written_ != 0)) clear();
}

od::SdoAbort InterpolationBuffer::write(std::int32_t record) {
  sync_configuration();
  if (!open()) return od::SdoAbort::WrongState;
  if (ring()) {
    // Ring: the record goes to the slot 60C4h-04h names; 04h then points at the next one (L2520-L2527).
    const std::size_t bound = size_.get() >= 1 && size_.get() <= kMaxRecords ? size_.get() : kMaxRecords;
    const std::size_t slot = position_.get();
    if (slot >= bound) return od::SdoAbort::ValueRangeExceeded;
    records_[slot] = record;
    written_ = std::max(written_, slot + 1);
    position_.set(static_cast<std::uint16_t>((slot + 1) % bound));
    return od::SdoAbort::Ok;
  }
  // FIFO: always at the tail (L2520-L2524).
  if (count_ >= fifo_capacity()) return od::SdoAbort::CannotTransfer;
  records_[(head_ + count_) % kMaxRecords] = record;
  ++count_;
  position_.set(static_cast<std::uint16_t>((head_ + count_) % kMaxRecords));
  return od::SdoAbort::Ok;
}

bool InterpolationBuffer::read(std::int32_t& record) {
  sync_configuration();
  if (ring()) {
    const std::size_t length = ring_length();
    if (length == 0) return false;
    if (head_ >= length) head_ = 0;
    record = records_[head_];
    head_ = (head_ + 1) % length;  // past the end it starts again at the top (L2598-L2606)
    return true;
  }
  if (count_ == 0) return false;  // the read pointer caught the write pointer (L2582-L2592)
  record = records_[head_];
  head_ = (head_ + 1) % kMaxRecords;
  --count_;
  return true;
}

// --- InterpolatedPositionMode --------------------------------------------------------------------

InterpolatedPositionMode::InterpolatedPositionMode(const DriveContext& ctx)
    : ctx_(ctx), buffer_(std::make_shared<InterpolationBuffer>(ctx.objects)), record_(ctx.objects, 0x60C1, 1),
      halt_(ctx.objects), following_error_(ctx.objects) {
  // The hooks hold the buffer, not the mode, so a write after the mode is gone stays harmless.
  std::shared_ptr<InterpolationBuffer> buffer = buffer_;
  ctx.objects.on_write(0x60C1, [buffer](const od::EntryDesc& e, std::span<const std::uint8_t> data) {
    if (e.subindex != 1) return od::SdoAbort::Ok;
    std::uint32_t raw = 0;
    std::memcpy(&raw, data.data(), std::min<std::size_t>(data.size(), sizeof(raw)));
    return buffer->write(static_cast<std::int32_t>(raw));
  });
  ctx.objects.on_write(0x60C4, [buffer](const od::EntryDesc& e, std::span<const std::uint8_t> data) {
    if (e.subindex == 6 && !data.empty() && data[0] == 0) buffer->clear();
    return od::SdoAbort::Ok;
  });
}

bool InterpolatedPositionMode::record_mapped_to_rxpdo() const {
  using firmware::pdo::read_unsigned;
  const std::uint32_t assigned = std::min<std::uint32_t>(read_unsigned(ctx_.objects, 0x1C12, 0), 255);
  for (std::uint32_t a = 1; a <= assigned; ++a) {
    const auto pdo = static_cast<std::uint16_t>(read_unsigned(ctx_.objects, 0x1C12, static_cast<std::uint8_t>(a)));
    const std::uint32_t entries = std::min<std::uint32_t>(read_unsigned(ctx_.objects, pdo, 0), 255);
    for (std::uint32_t i = 1; i <= entries; ++i) {
      const auto entry = ecat::PdoMappingEntry::decode(read_unsigned(ctx_.objects, pdo, static_cast<std::uint8_t>(i)));
      if (entry.index == 0x60C1 && entry.subindex == 1) return true;
    }
  }
  return false;
}

void InterpolatedPositionMode::on_cycle(Nanos now) {
  // The mapping only changes in Pre-Op, when no cycles run: look again when cycles (re)start.
  if (last_cycle_ < 0 || now - last_cycle_ > 100'000'000) record_in_pdo_ = record_mapped_to_rxpdo();
  last_cycle_ = now;
  if (record_in_pdo_) buffer_->write(record_.get());  // a full or closed buffer drops it
}

void InterpolatedPositionMode::hold(double position) {
  output_ = position;
  from_ = to_ = position;
  into_ = 0;
  interpolating_ = false;
  halted_ = false;
}

void InterpolatedPositionMode::activate(const AxisSample& s) {
  hold(s.position_demand);
  following_error_.reset();
  status_ = 0;
}

void InterpolatedPositionMode::idle(const AxisSample& s, std::uint16_t) {
  buffer_->sync_configuration();
  hold(s.position);
  following_error_.reset();
  status_ = 0;
}

Setpoint InterpolatedPositionMode::step(const AxisSample& s, std::uint16_t controlword) {
  constexpr double period_s = static_cast<double>(kInterpolationPeriod) * 1e-9;
  const Nanos dt = static_cast<Nanos>(std::llround(s.dt_s * 1e9));
  const bool enabled = (controlword & cw::new_set_point) != 0;  // bit 4: enable interpolation
  buffer_->sync_configuration();
  Setpoint sp;
  sp.kind = Setpoint::Kind::Position;

  if (controlword & cw::halt) {
    if (!halted_) halting_ = {output_, interpolating_ ? (to_ - from_) / period_s : 0.0};
    halted_ = true;
    interpolating_ = false;
    halting_ = ramp_velocity(halting_, 0.0, halt_.deceleration(), halt_.deceleration(), s.dt_s);
    output_ = halting_.position;
    sp.velocity = halting_.velocity;
  } else {
    halted_ = false;
    if (!enabled) {
      interpolating_ = false;  // the demand stays where it is
    } else {
      std::int32_t record = 0;
      if (interpolating_) {
        into_ += dt;
      } else if (buffer_->read(record)) {
        from_ = output_;
        to_ = record;
        into_ = dt;
        interpolating_ = true;
      }
      while (interpolating_ && into_ >= kInterpolationPeriod) {
        into_ -= kInterpolationPeriod;
        if (buffer_->read(record)) {
          from_ = to_;
          to_ = record;
        } else {
          output_ = to_;  // FIFO ran out: motion ends on the last record
          interpolating_ = false;
        }
      }
      if (interpolating_) {
        output_ = from_ + (to_ - from_) * static_cast<double>(into_) / static_cast<double>(kInterpolationPeriod);
        sp.velocity = (to_ - from_) / period_s;
      }
    }
  }
  sp.position = output_;

  status_ = 0;
  if (halted_ ? halting_.velocity == 0.0 : !interpolating_) status_ |= sw::target_reached;
  if (enabled && !halted_) status_ |= sw::oms12;
  if (following_error_.update(s)) status_ |= sw::oms13;
  return sp;
}

}  // namespace vdrive::drive
