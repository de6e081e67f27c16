#include "esc_model/sync_manager.hpp"

#include <algorithm>

#include "ethercat/little_endian.hpp"
#include "ethercat/registers.hpp"

namespace vdrive::esc {

namespace {
constexpr int kBufferCount = 3;
constexpr std::uint8_t kNoBufferWritten = 3;
}  // namespace

void SyncManager::configure(Registers regs) {
  start_ = ecat::get_le16(regs, ecat::reg::sm::kStart);
  length_ = ecat::get_le16(regs, ecat::reg::sm::kLength);
  const std::uint8_t control = regs[ecat::reg::sm::kControl];
  mailbox_ = (control & ecat::reg::sm::kModeMask) == ecat::reg::sm::kModeMailbox;
  writer_ = (control & ecat::reg::sm::kDirectionMask) == ecat::reg::sm::kDirectionEcatWrites
                ? Side::Ecat
                : Side::Pdi;
  ecat_event_enable_ = (control & ecat::reg::sm::kEcatEventEnable) != 0;
  al_event_enable_ = (control & ecat::reg::sm::kAlEventEnable) != 0;
  watchdog_trigger_ = (control & ecat::reg::sm::kWatchdogTrigger) != 0;
  const bool enable = (regs[ecat::reg::sm::kActivate] & ecat::reg::sm::kEnable) != 0 &&
                      (regs[ecat::reg::sm::kPdiControl] & ecat::reg::sm::kPdiDeactivate) == 0;
  if (enable != enabled_) reset_state();
  enabled_ = enable;
}

void SyncManager::reset_state() {
  full_ = false;
  irq_write_ = false;
  irq_read_ = false;
  read_open_ = false;
  write_open_ = false;
  newest_ = kNone;
  read_buffer_ = 0;
  write_buffer_ = 0;
}

std::uint32_t SyncManager::buffer_address(int buffer, std::uint16_t address) const {
  return static_cast<std::uint32_t>(address) +
         static_cast<std::uint32_t>(buffer) * static_cast<std::uint32_t>(length_);
}

int SyncManager::free_buffer() const {
  for (int b = 0; b < kBufferCount; ++b) {
    if (b != newest_ && !(read_open_ && b == read_buffer_)) return b;
  }
  return 0;  // unreachable: three buffers, at most two taken
}

bool SyncManager::event_for(Side side) const {
  // The write interrupt is signalled to the reader, the read interrupt to the writer.
  return side == writer_ ? irq_read_ : irq_write_;
}

namespace {
// Copies what lies in backed memory; bytes beyond it read as 0 (reads) or are dropped (writes).
void copy_out(std::span<const std::uint8_t> memory, std::uint32_t at, std::span<std::uint8_t> out) {
  const std::size_t backed = at < memory.size() ? std::min<std::size_t>(out.size(), memory.size() - at) : 0;
  if (backed != 0) std::copy_n(memory.begin() + at, backed, out.begin());
  std::fill(out.begin() + static_cast<std::ptrdiff_t>(backed), out.end(), std::uint8_t{0});
}

void copy_in(std::span<std::uint8_t> memory, std::uint32_t at, std::span<const std::uint8_t> in,
             std::uint8_t mask) {
  const std::size_t backed = at < memory.size() ? std::min<std::size_t>(in.size(), memory.size() - at) : 0;
  if (mask == 0xFF) {
    if (backed != 0) std::copy_n(in.begin(), backed, memory.begin() + at);
    return;
  }
  for (std::size_t i = 0; i < backed; ++i) {
    memory[at + i] = static_cast<std::uint8_t>((memory[at + i] & ~mask) | (in[i] & mask));
  }
}
}  // namespace

// A run is what the same bytes accessed one by one in ascending order give: the buffer can only
// open at the run's first byte (a later byte is never the window's first) and only close at its
// last (the window's last byte ends every run that holds it), so the state changes at the ends.
SyncManager::Result SyncManager::read(Side side, std::uint16_t address, std::span<std::uint8_t> out,
                                      std::span<const std::uint8_t> memory) {
  if (out.empty()) return {};
  const bool first = address == start_;
  const bool last = address - start_ + out.size() == length_;
  if (mailbox_) {
    if (side == writer_) {
      copy_out(memory, address, out);
      return {true, false};
    }
    if (!full_) return {};  // empty read mailbox: no data, no working counter
    if (first || !read_open_) {
      read_open_ = true;
      irq_write_ = false;
    }
    copy_out(memory, address, out);
    if (last) {
      full_ = false;
      read_open_ = false;
      irq_read_ = true;
    }
    return {true, false};
  }
  if (side == writer_) {
    const int b = write_open_ ? write_buffer_ : (newest_ == kNone ? 0 : newest_);
    copy_out(memory, buffer_address(b, address), out);
    return {true, false};
  }
  if (first || !read_open_) {
    read_open_ = true;
    if (newest_ != kNone) read_buffer_ = newest_;
    irq_write_ = false;
  }
  copy_out(memory, buffer_address(read_buffer_, address), out);
  if (last) {
    read_open_ = false;
    irq_read_ = true;
  }
  return {true, false};
}

SyncManager::Result SyncManager::write(Side side, std::uint16_t address,
                                       std::span<const std::uint8_t> in, std::uint8_t mask,
                                       std::span<std::uint8_t> memory) {
  if (side != writer_ || in.empty()) return {};
  const bool first = address == start_;
  const bool last = address - start_ + in.size() == length_;
  std::uint32_t at = address;
  if (mailbox_) {
    if (full_) return {};  // full mailbox: write rejected, no working counter
    if (first || !write_open_) {
      write_open_ = true;
      irq_read_ = false;
    }
  } else {
    if (!write_open_) {
      write_open_ = true;
      write_buffer_ = free_buffer();
      irq_read_ = false;
    } else if (first) {
      irq_read_ = false;
    }
    at = buffer_address(write_buffer_, address);
  }
  copy_in(memory, at, in, mask);
  if (!last) return {true, false};
  write_open_ = false;
  irq_write_ = true;
  if (mailbox_) {
    full_ = true;
  } else {
    newest_ = write_buffer_;
  }
  return {true, true};
}

std::uint8_t SyncManager::status() const {
  if (!enabled_) return 0;
  std::uint8_t s = 0;
  if (irq_write_) s |= ecat::reg::sm::kIrqWrite;
  if (irq_read_) s |= ecat::reg::sm::kIrqRead;
  if (mailbox_) {
    if (full_) s |= ecat::reg::sm::kMailboxFull;
  } else {
    const std::uint8_t state = newest_ == kNone ? kNoBufferWritten
                                                : static_cast<std::uint8_t>(newest_);
    s |= static_cast<std::uint8_t>(state << ecat::reg::sm::kBufferStateShift);
  }
  if (read_open_) s |= ecat::reg::sm::kReadBufferOpen;
  if (write_open_) s |= ecat::reg::sm::kWriteBufferOpen;
  return s;
}

}  // namespace vdrive::esc
