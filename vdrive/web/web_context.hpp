#pragma once
// What the API's handlers share (web_server.cpp builds it, api_routes.cpp uses it): the record,
// the way to the loop, and what is fixed from start-up. Internal to vdrive/web.
#include <atomic>
#include <functional>
#include <mutex>
#include <string_view>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/clock.hpp"
#include "vdrive/control/control_request.hpp"
#include "vdrive/fault/fault_spec.hpp"
#include "vdrive/od/dictionary.hpp"
#include "vdrive/web/api_result.hpp"
#include "vdrive/web/line_record.hpp"
#include "vdrive/web/loop_calls.hpp"
#include "vdrive/web/part_pages.hpp"

namespace httplib { class Server; }
namespace vdrive::network { class Network; }
namespace vdrive::control { class FaultService; }

namespace vdrive::web {

// How long a request waits for the loop before it answers 503.
constexpr Nanos kLoopTimeout = 2'000'000'000;

struct ScheduledFault {
  int ticket = 0;
  Nanos at = 0;  // on the line's clock
  control::ControlRequest request;
  std::string line;  // the request as the control protocol writes it
  nlohmann::json fault;  // as it was asked for
};

struct WebContext {
  network::Network& network;
  const Clock& clock;
  control::FaultService* faults;
  LineRecord& record;
  LoopCalls& calls;
  std::vector<const od::Dictionary*> dictionaries;  // per slave, immutable
  std::mutex scheduled_mutex;
  std::vector<ScheduledFault> scheduled;
  int next_ticket = 1;
  // A line over processes: the later parts' pages (empty otherwise), and the run's router that
  // fault and signal requests go through (unset: this process's alone).
  PartPages* parts = nullptr;
  std::function<control::ControlReply(const control::ControlRequest&, std::string_view)> route;

  // Carries out a fault request (`line`: as the control protocol writes it) through the router,
  // or else on the loop thread; a failed reply when the loop does not answer.
  control::ControlReply fault_call(const control::ControlRequest& request, std::string_view line);
};

// The JSON API's routes (docs/web.md, assets/openapi.json).
void add_api_routes(httplib::Server& server, WebContext& context);

}  // namespace vdrive::web
