#pragma once
// Turns SIGINT/SIGTERM into a stop request for the event loop. The handler only sets an atomic
// flag (async-signal-safe); it is installed without SA_RESTART so a waiting receive() returns at
// once, and with SA_RESETHAND so a second signal ends a process that does not stop in time.
#include <atomic>

namespace vdrive::runtime {

// Installs the handlers (idempotent) and returns the flag they set.
std::atomic<bool>& stop_on_termination_signals();

}  // namespace vdrive::runtime
