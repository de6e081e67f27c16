#pragma once
// PartRouter: part 1's control socket in front of every part of `vdrive run --processes N`
// (docs/scale-out.md, "Faults over the parts"). Each later part serves its own control socket at
// a private path; part 1's socket stays the run's one address, and this routes each request
// line there by slave:
//   - a fault for a position in a later part goes to that part with the position made local
//     (position minus the slaves before the part); wire faults (they act at part 1's port to the
//     master), positions in part 1 and positions beyond the line stay here;
//   - a station address part 1 does not have is asked of the later parts in order
//     (find_station) and the request goes to the one that has it; if none has it the error says
//     no part of the line has it;
//   - `clear ID` goes to the part the run-wide id names (run_fault_id.hpp); `list`, `clear_all`,
//     `find_station` and `line_status` ask every part and merge the answers;
//   - signals (a network file's, each part serving those of its slaves): `signals` asks every
//     part and lists them in line order; a named signal, or a point at a named slave ("x.home"),
//     is asked of part 1, then of the later parts in order, until one has it; a point at a
//     position ("3 0x6010:1") goes to the part that serves it with the position made local;
//   - replies come back with run-wide ids, and "slave N" in a later part's descriptions and errors
//     and a position in its signal points as the whole line's position.
// A later part that has ended or does not answer within the timeout is an error naming the part
// and its slaves ("part 2 (slave 3) does not answer: ..."); a fan-out still reports what the
// other parts did.
//
// Runs on the control socket's thread (ControlServer's handler), never on the event loop: a part
// that hangs delays only this thread. Part 1's own requests go through `local` (FaultService::call).
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "common/clock.hpp"
#include "vdrive/control/control_request.hpp"

namespace vdrive::control {

// A later part as part 1 sees it.
struct RemotePart {
  std::size_t first = 0;  // 0-based index of its first slave in the whole line
  std::size_t count = 0;
  std::string socket;     // its control socket
};

class PartRouter {
public:
  // Part 1's own service: a request -> its reply (ids and positions part 1's own).
  using Local = std::function<ControlReply(const ControlRequest&)>;
  // One round trip to a part's socket (control_call; tests give their own). Throws
  // ControlSocketError when nothing listens or no reply comes within `timeout`.
  using Call = std::function<std::string(const std::string& path, std::string_view line, Nanos timeout)>;

  static constexpr Nanos kPartTimeout = 1'000'000'000;

  // `own_slaves`: part 1's slaves (1..own_slaves); `later`: parts 2..N in line order.
  PartRouter(std::size_t own_slaves, std::vector<RemotePart> later, Local local, Call call, Nanos timeout = kPartTimeout);

  // A request line -> the reply line for the user.
  std::string answer(std::string_view line);
  // The same on a parsed request (`line` is what was parsed, forwarded with its fields as given).
  ControlReply route(const ControlRequest& request, std::string_view line);

  std::size_t parts() const { return later_.size() + 1; }
  // "part 2 (slave 3)", "part 3 (slaves 4-5)": `part` 0-based among the later parts' numbering
  // (0 is part 1).
  std::string part_name(std::size_t part) const;

private:
  ControlReply inject(const ControlRequest& request, std::string_view line);
  ControlReply inject_at_station(const ControlRequest& request, std::string_view line);
  ControlReply clear(const ControlRequest& request);
  ControlReply fan_out(const ControlRequest& request);
  ControlReply find_station(const ControlRequest& request, std::string_view line);
  // Every slave's AL state, part by part in line order; a part that does not answer is the error.
  ControlReply line_states(const ControlRequest& request);
  ControlReply list_signals(const ControlRequest& request);
  ControlReply signal(const ControlRequest& request, std::string_view line);
  // A point whose slave is a whole-line position, in the part that serves it.
  ControlReply signal_at(const ControlRequest& request, std::string_view line, std::uint64_t position);
  // A named signal, or a point at a named slave: part 1 first, then the later parts in order.
  ControlReply signal_anywhere(const ControlRequest& request, std::string_view line);
  // One request line to later part `part` (1-based in parts(), >= 1); the reply with positions
  // and ids as part 1 shows them, or a `failed` reply naming the part.
  ControlReply forward(std::size_t part, const std::string& line);
  std::size_t first_of(std::size_t part) const { return part == 0 ? 0 : later_[part - 1].first; }
  std::size_t line_slaves() const;
  // The part (0 = part 1) that serves whole-line position `position` (from 1); 0 beyond the line.
  std::size_t part_at(std::size_t position) const;

  std::size_t own_slaves_;
  std::vector<RemotePart> later_;
  Local local_;
  Call call_;
  Nanos timeout_;
};

// `text` with every "slave N" (N a number) as "slave N+offset": a later part's description or
// error in the whole line's positions. Station addresses ("slave 0x1003") are left alone.
std::string shift_slave_numbers(std::string_view text, std::size_t offset);

}  // namespace vdrive::control
