#include "esc_model/sync_manager.hpp"

#include "esc_model/registers.hpp"

namespace vdrive::esc {

namespace {
constexpr int kBufferCount = 3;
constexpr std::uint8_t kNoBufferWritten = 3;
}  // namespace

void SyncManager::configure(Registers regs) {
  start_ = static_cast<std::uint16_t>(regs[reg::sm::kStart] | (regs[reg::sm::kStart + 1] << 8));
  length_ =
      static_cast<std::uint16_t>(regs[reg::sm::kLength] | (regs[reg::sm::kLength + 1] << 8));
  const std::uint8_t control = regs[reg::sm::kControl];
  mailbox_ = (control & reg::sm::kModeMask) == reg::sm::kModeMailbox;
  writer_ = (control & reg::sm::kDirectionMask) == reg::sm::kDirectionEcatWrites ? Side::Ecat
                                                                                  : Side::Pdi;
  ecat_event_enable_ = (control & reg::sm::kEcatEventEnable) != 0;
  al_event_enable_ = (control & reg::sm::kAlEventEnable) != 0;
  watchdog_trigger_ = (control & reg::sm::kWatchdogTrigger) != 0;
  const bool enable = (regs[reg::sm::kActivate] & reg::sm::kEnable) != 0 &&
                      (regs[reg::sm::kPdiControl] & reg::sm::kPdiDeactivate) == 0;
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

SyncManager::Result SyncManager::read(Side side, std::uint16_t address, std::uint8_t& out,
                                      std::span<const std::uint8_t> memory) {
  const bool first = address == start_;
  const bool last = address - start_ == length_ - 1;
  if (mailbox_) {
    if (side == writer_) {
      out = address < memory.size() ? memory[address] : 0;
      return {true, false};
    }
    if (!full_) return {};  // empty read mailbox: no data, no working counter
    if (first || !read_open_) {
      read_open_ = true;
      irq_write_ = false;
    }
    out = address < memory.size() ? memory[address] : 0;
    if (last) {
      full_ = false;
      read_open_ = false;
      irq_read_ = true;
    }
    return {true, false};
  }
  if (side == writer_) {
    const int b = write_open_ ? write_buffer_ : (newest_ == kNone ? 0 : newest_);
    const std::uint32_t at = buffer_address(b, address);
    out = at < memory.size() ? memory[at] : 0;
    return {true, false};
  }
  if (first || !read_open_) {
    read_open_ = true;
    if (newest_ != kNone) read_buffer_ = newest_;
    irq_write_ = false;
  }
  const std::uint32_t at = buffer_address(read_buffer_, address);
  out = at < memory.size() ? memory[at] : 0;
  if (last) {
    read_open_ = false;
    irq_read_ = true;
  }
  return {true, false};
}

SyncManager::Result SyncManager::write(Side side, std::uint16_t address, std::uint8_t value,
                                       std::uint8_t mask, std::span<std::uint8_t> memory) {
  if (side != writer_) return {};
  const bool first = address == start_;
  const bool last = address - start_ == length_ - 1;
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
  if (at < memory.size()) {
    memory[at] = static_cast<std::uint8_t>((memory[at] & ~mask) | (value & mask));
  }
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
  if (irq_write_) s |= reg::sm::kIrqWrite;
  if (irq_read_) s |= reg::sm::kIrqRead;
  if (mailbox_) {
    if (full_) s |= reg::sm::kMailboxFull;
  } else {
    const std::uint8_t state = newest_ == kNone ? kNoBufferWritten
                                                : static_cast<std::uint8_t>(newest_);
    s |= static_cast<std::uint8_t>(state << reg::sm::kBufferStateShift);
  }
  if (read_open_) s |= reg::sm::kReadBufferOpen;
  if (write_open_) s |= reg::sm::kWriteBufferOpen;
  return s;
}

}  // namespace vdrive::esc
