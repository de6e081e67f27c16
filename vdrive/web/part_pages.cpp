#include "vdrive/web/part_pages.hpp"

#include <fmt/format.h>
#include <httplib.h>

#include "vdrive/control/part_router.hpp"
#include "vdrive/network/line_parts.hpp"
#include "vdrive/web/line_record.hpp"

namespace vdrive::web {
namespace {

using json = nlohmann::json;

std::string failure(httplib::Error e, int port) {
  switch (e) {
    case httplib::Error::Connection: return fmt::format("cannot connect to its page on 127.0.0.1:{}", port);
    case httplib::Error::ConnectionTimeout:
      return fmt::format("no connection to its page on 127.0.0.1:{} within {} s", port, PartPages::kTimeoutSeconds);
    case httplib::Error::Read: return fmt::format("its page on 127.0.0.1:{} sent no answer within {} s", port, PartPages::kTimeoutSeconds);
    default: return fmt::format("its page on 127.0.0.1:{}: {}", port, httplib::to_string(e));
  }
}

}  // namespace

PartPages::PartPages(std::vector<PartPage> parts, std::string token) : token_(std::move(token)) {
  for (PartPage& p : parts) parts_.push_back({p, 0, 0, true});
}

std::size_t PartPages::slaves() const {
  std::size_t n = 0;
  for (const Part& p : parts_) n += p.page.count;
  return n;
}

std::optional<std::size_t> PartPages::part_of(std::size_t slave) const {
  for (std::size_t k = 0; k < parts_.size(); ++k)
    if (slave >= parts_[k].page.first && slave < parts_[k].page.first + parts_[k].page.count) return k;
  return std::nullopt;
}

std::string PartPages::name(std::size_t part) const {
  const PartPage& p = parts_[part].page;
  return network::part_name(part + 1, {p.first, p.count});  // part 1 is the caller's own
}

ApiResult PartPages::call(std::size_t part, const std::string& method, const std::string& path, const std::string& body) const {
  const PartPage& p = parts_[part].page;
  httplib::Client client("127.0.0.1", p.port);
  client.set_connection_timeout(kTimeoutSeconds, 0);
  client.set_read_timeout(kTimeoutSeconds, 0);
  client.set_write_timeout(kTimeoutSeconds, 0);
  httplib::Headers headers;
  if (!token_.empty()) headers.emplace("Authorization", "Bearer " + token_);
  httplib::Result r = method == "GET"    ? client.Get(path.c_str(), headers)
                      : method == "PUT"  ? client.Put(path.c_str(), headers, body, "application/json")
                      : method == "POST" ? client.Post(path.c_str(), headers, body, "application/json")
                                         : client.Delete(path.c_str(), headers, body, "application/json");
  if (!r) return api_error(503, fmt::format("{} does not answer (has it ended?): {}", name(part), failure(r.error(), p.port)));
  ApiResult result{r->status, nullptr};
  try {
    result.body = json::parse(r->body);
  } catch (const json::exception& e) {
    return api_error(502, fmt::format("{} answered what is not JSON: {}", name(part), e.what()));
  }
  if (result.body.is_object() && result.body.contains("error") && result.body["error"].is_string())
    result.body["error"] = control::shift_slave_numbers(result.body["error"].get<std::string>(), p.first);
  return result;
}

ApiResult PartPages::call_for_slave(std::size_t slave, const std::string& method, const std::string& rest, const std::string& body) const {
  const std::size_t part = part_of(slave).value();
  return call(part, method, fmt::format("/api/v1/slaves/{}{}", slave - parts_[part].page.first + 1, rest), body);
}

void PartPages::poll(LineRecord& record, Nanos now) {
  for (std::size_t k = 0; k < parts_.size(); ++k) {
    Part& p = parts_[k];
    try {
      const ApiResult line = call(k, "GET", "/api/v1/line");
      if (line.status != 200) {
        if (p.answering) {
          const std::string why = line.body.is_object() && line.body.contains("error") ? line.body["error"].get<std::string>()
                                                                                        : fmt::format("HTTP {}", line.status);
          record.set_part_silent(p.page.first, p.page.count, why, now);
        }
        p.answering = false;
        continue;
      }
      record.set_part_line(p.page.first, line.body);
      if (!p.answering) record.note(static_cast<int>(p.page.first + 1), "part_answers", 0, 0, name(k) + " answers again", now);
      p.answering = true;
      const ApiResult samples = call(k, "GET", fmt::format("/api/v1/samples?since={}", p.samples_seen));
      if (samples.status == 200) {
        record.add_part_samples(p.page.first, samples.body);
        p.samples_seen = samples.body.at("seq").get<std::uint64_t>();
      }
      const ApiResult events = call(k, "GET", fmt::format("/api/v1/events?since={}", p.events_seen));
      if (events.status == 200) {
        record.add_part_events(p.page.first, events.body);
        p.events_seen = events.body.at("seq").get<std::uint64_t>();
      }
    } catch (const json::exception& e) {  // a page of another version: say so once, keep the rest
      if (p.answering) record.set_part_silent(p.page.first, p.page.count, fmt::format("{}: unexpected answer: {}", name(k), e.what()), now);
      p.answering = false;
    }
  }
}

}  // namespace vdrive::web
