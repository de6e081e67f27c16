#pragma once
// PartPages: the pages of the later parts of `vdrive run --processes N`, as part 1's page reaches
// them (docs/scale-out.md, "The web page over the parts"). Each later part serves the same JSON
// API on a loopback port of its own, and only part 1 changes anything there (a token the run
// makes). Part 1's page
//   - reads each part's line, new plot points and new events into its own record (poll), so the
//     page, the stream and the API show one line in whole-line positions;
//   - sends a request for one of their slaves (objects, alarms, plant) on to the part that serves
//     it, with the slave's position made the part's own, and its answer back with "slave N" in
//     whole-line positions.
// A part that does not answer within its timeout is a 503 naming it; poll marks its slaves so.
// Called on the web server's threads, never on the event loop.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/clock.hpp"
#include "vdrive/web/api_result.hpp"

namespace vdrive::web {

class LineRecord;

// A later part's page.
struct PartPage {
  std::size_t first = 0;  // 0-based index of its first slave in the whole line
  std::size_t count = 0;
  int port = 0;           // its page on 127.0.0.1
};

class PartPages {
public:
  static constexpr int kTimeoutSeconds = 3;  // longer than a part's own wait for its loop (2 s)

  // `parts` in line order; `token`: what their pages ask of a change.
  PartPages(std::vector<PartPage> parts, std::string token);

  bool empty() const { return parts_.empty(); }
  // The slaves of all later parts.
  std::size_t slaves() const;
  // The later part (index into the parts) that serves whole-line index `slave`; none for part 1's.
  std::optional<std::size_t> part_of(std::size_t slave) const;
  const PartPage& page(std::size_t part) const { return parts_[part].page; }
  // "part 2 (slave 3)", "part 3 (slaves 4-5)".
  std::string name(std::size_t part) const;

  // One request to part `part`: `path` with its query, in the part's own positions; the answer
  // with "slave N" of its error in whole-line positions, or a 503 naming the part.
  ApiResult call(std::size_t part, const std::string& method, const std::string& path, const std::string& body = {}) const;
  // The same for a request about whole-line slave index `slave` of that part: `rest` follows
  // "/api/v1/slaves/POS" (POS made the part's own).
  ApiResult call_for_slave(std::size_t slave, const std::string& method, const std::string& rest, const std::string& body = {}) const;

  // Every part's line, and its plot points and events since the last poll, into `record`; `now`
  // on the record's clock, for the events a part's silence makes.
  void poll(LineRecord& record, Nanos now);

private:
  struct Part {
    PartPage page;
    std::uint64_t samples_seen = 0, events_seen = 0;
    bool answering = true;
  };
  std::vector<Part> parts_;
  std::string token_;
};

}  // namespace vdrive::web
