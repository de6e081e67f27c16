#pragma once
// A protocol carried in the mailbox (CoE now, FoE later). The mailbox module hands it each
// request's payload (the bytes after the 6-byte header) and a reply area in one of its fixed
// buffers; the protocol writes its reply payload there. Nothing here may allocate.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "common/clock.hpp"
#include "ethercat/mailbox_header.hpp"

namespace vdrive::firmware::mailbox {

// What a protocol made of a request: a reply payload of `length` bytes (0 = no reply), or a
// mailbox error reply instead (the request was not understood at the mailbox level).
struct Outcome {
  std::size_t length = 0;
  std::optional<ecat::mailbox::ErrorCode> error;

  static Outcome reply(std::size_t n) { return {n, std::nullopt}; }
  static Outcome none() { return {}; }
  static Outcome mailbox_error(ecat::mailbox::ErrorCode code) { return {0, code}; }
};

class Protocol {
public:
  virtual ~Protocol() = default;
  // One request. `reply` is as large as the master's SM1 allows (minus the header).
  virtual Outcome on_request(std::span<const std::uint8_t> request, std::span<std::uint8_t> reply,
                             Nanos now) = 0;
  // Further replies to the last request (fragments); called whenever a reply buffer is free.
  // Returns the payload length written, 0 when there is nothing more.
  virtual std::size_t next_reply(std::span<std::uint8_t> /*reply*/) { return 0; }
  // The mailbox stopped (slave back to Init): forget transfers in progress.
  virtual void reset() {}
};

}  // namespace vdrive::firmware::mailbox
