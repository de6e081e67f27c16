// The JSON API through HTTP: every endpoint, and the refusals a bad request gets.
#include <gtest/gtest.h>

#include "tests/web/web_line.hpp"

namespace vdrive::web::test {
namespace {

using json = nlohmann::json;
constexpr const char* kJson = "application/json";

TEST(WebApi, LineDescribesEverySlave) {
  WebLine line;
  // The drive's state comes with the samples (50 Hz), the AL state with the registers (10 Hz).
  ASSERT_TRUE(eventually([&] {
    const json l = line.get("/api/v1/line");
    return l["slaves"][0]["drive"]["state"] != "unknown" && l["slaves"][0]["al_state_name"] != "unknown";
  }));
  const json j = line.get("/api/v1/line");
  EXPECT_EQ(j["api"], "v1");
  EXPECT_EQ(j["token_required"], false);
  ASSERT_EQ(j["slaves"].size(), 3u);
  EXPECT_EQ(j["slaves"][0]["position"], 1);
  EXPECT_EQ(j["slaves"][0]["product"], "a6b");
  EXPECT_EQ(j["slaves"][1]["product"], "ds5c1");
  EXPECT_EQ(j["slaves"][0]["al_state_name"], "Init");
  EXPECT_EQ(j["slaves"][0]["rx_errors"].size(), 4u);
  // No master has enabled anything: the drive sits in Switch on disabled.
  EXPECT_EQ(j["slaves"][0]["drive"]["state"], "Switch on disabled");
  EXPECT_EQ(j["slaves"][0]["drive"]["alarm"], nullptr);
}

TEST(WebApi, SamplesComeWithSequenceNumbersAndOnlyNewOnesOnRequest) {
  WebLine line;
  ASSERT_TRUE(eventually([&] { return line.get("/api/v1/samples")["seq"].get<std::uint64_t>() > 6; }));
  const json all = line.get("/api/v1/samples?slave=2");
  ASSERT_EQ(all["axes"].size(), 1u);
  EXPECT_EQ(all["axes"][0]["slave"], 2);
  EXPECT_FALSE(all["axes"][0]["t"].empty());
  EXPECT_EQ(all["axes"][0]["t"].size(), all["axes"][0]["position"].size());
  const std::uint64_t seq = all["seq"];
  const json newer = line.get("/api/v1/samples?since=" + std::to_string(seq));
  for (const json& axis : newer["axes"])
    for (const json& t : axis["t"]) EXPECT_GT(t.get<double>(), all["axes"][0]["t"].back().get<double>() - 1.0);
  EXPECT_LT(newer["axes"][0]["t"].size(), all["axes"][0]["t"].size() + 3);
}

// A host stall of the line's loop (docs/reliability.md) is in the event log, kind host_stall, with
// its length and what the drives saw, and the line's counters count it.
TEST(WebApi, HostStallsAreEventsAndCounted) {
  WebLine line;
  runtime::HostStall s;
  s.time = 1'000'000;
  s.length = 12'340'000;
  s.threshold = 2'000'000;
  s.sync0_slaves = s.step_slaves = 0b111;
  s.sync0_pulses = 13;
  s.control_steps = 98;
  line.stalls().record(s);
  ASSERT_TRUE(eventually([&] { return !line.get("/api/v1/events?kind=host_stall")["events"].empty(); }));
  const json e = line.get("/api/v1/events?kind=host_stall")["events"][0];
  EXPECT_EQ(e["slave"], 0);
  EXPECT_EQ(e["value"], 12'340);
  EXPECT_EQ(e["previous"], 2'000);
  EXPECT_EQ(e["text"], "host stall 12.3 ms (threshold 2.0 ms): slaves 1-3 missed 12 SYNC0 pulses and caught up 98 control steps");
  ASSERT_TRUE(eventually([&] { return line.get("/api/v1/line")["counters"]["host_stalls"] == 1; }));
  EXPECT_EQ(line.get("/api/v1/line")["counters"]["longest_host_stall_ns"], 12'340'000);
}

TEST(WebApi, BadQueryParametersAreNamed) {
  WebLine line;
  auto r = line.client().Get("/api/v1/samples?since=abc");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400);
  EXPECT_NE(json::parse(r->body)["error"].get<std::string>().find("since"), std::string::npos);
  r = line.client().Get("/api/v1/events?slave=9");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400);
  EXPECT_NE(json::parse(r->body)["error"].get<std::string>().find("slave"), std::string::npos);
}

TEST(WebApi, ASlaveIsAPositionOrItsStationAddress) {
  WebLine line;
  auto c = line.client();
  auto r = c.Get("/api/v1/slaves/0x1002/alarms");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 404);
  EXPECT_NE(json::parse(r->body)["error"].get<std::string>().find("no master has set station addresses yet"), std::string::npos)
      << r->body;

  ASSERT_TRUE(line.assign_station_addresses(0x1001));
  ASSERT_TRUE(eventually([&] { return line.get("/api/v1/line")["slaves"][1]["address"] == 0x1002; }));
  EXPECT_EQ(line.get("/api/v1/slaves/0x1002/objects/0x1018/1")["value"], line.get("/api/v1/slaves/2/objects/0x1018/1")["value"]);
  EXPECT_EQ(line.get("/api/v1/slaves/0x1002/alarms"), line.get("/api/v1/slaves/2/alarms"));
  ASSERT_TRUE(eventually([&] { return line.get("/api/v1/samples")["seq"].get<std::uint64_t>() > 3; }));
  const json two = line.get("/api/v1/samples?slave=0x1002");
  ASSERT_EQ(two["axes"].size(), 1u);
  EXPECT_EQ(two["axes"][0]["slave"], 2);
  r = c.Get("/api/v1/events?slave=0x1009");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400);
  EXPECT_NE(json::parse(r->body)["error"].get<std::string>().find("no slave has station address 0x1009 (the line has 0x1001, 0x1002, 0x1003)"),
            std::string::npos)
      << r->body;
  r = c.Get("/api/v1/slaves/0x1009/objects/0x6041/0");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 404);
}

TEST(WebApi, ObjectsAreListedAndSearched) {
  WebLine line;
  const json byIndex = line.get("/api/v1/slaves/1/objects?q=0x6041");
  ASSERT_FALSE(byIndex["objects"].empty());
  EXPECT_EQ(byIndex["objects"][0]["index"], 0x6041);
  EXPECT_EQ(byIndex["objects"][0]["access"], "ro");
  const json byName = line.get("/api/v1/slaves/1/objects?q=controlword");
  bool found = false;
  for (const json& o : byName["objects"]) found = found || o["index"] == 0x6040;
  EXPECT_TRUE(found);
}

TEST(WebApi, ObjectReadGivesTheValue) {
  WebLine line;
  const json j = line.get("/api/v1/slaves/1/objects/0x1018/1");
  EXPECT_EQ(j["index"], 0x1018);
  EXPECT_EQ(j["value"], 0x066F);  // Panasonic's vendor id
  EXPECT_EQ(j["hex"], "6f060000");
}

TEST(WebApi, WritingAReadOnlyObjectGetsTheMastersAbortCode) {
  WebLine line;
  auto r = line.client().Put("/api/v1/slaves/1/objects/0x6041/0", R"({"value":1})", kJson);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 409);
  const json j = json::parse(r->body);
  EXPECT_EQ(j["abort_code"], "0x06010002");
  EXPECT_NE(j["error"].get<std::string>().find("6041h"), std::string::npos);
  // The refusal is an event of the log.
  ASSERT_TRUE(eventually([&] { return !line.get("/api/v1/events?kind=od_abort")["events"].empty(); }));
}

TEST(WebApi, AWriteIsStoredAndReadBack) {
  WebLine line;
  auto r = line.client().Put("/api/v1/slaves/1/objects/0x6060/0", R"({"value":8})", kJson);
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  EXPECT_EQ(json::parse(r->body)["value"], 8);
  EXPECT_EQ(line.get("/api/v1/slaves/1/objects/0x6060/0")["value"], 8);
}

TEST(WebApi, ObjectRefusalsNameWhatWasWrong) {
  WebLine line;
  auto c = line.client();
  auto r = c.Get("/api/v1/slaves/1/objects/0x5FFE/0");  // no such object
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 404);
  EXPECT_EQ(json::parse(r->body)["abort_code"], "0x06020000");
  r = c.Get("/api/v1/slaves/9/objects/0x6041/0");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 404);
  EXPECT_NE(json::parse(r->body)["error"].get<std::string>().find("slaves 1 to 3"), std::string::npos);
  r = c.Get("/api/v1/slaves/1/objects/0x1FFFF/0");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400);
  r = c.Put("/api/v1/slaves/1/objects/0x6060/0", R"({"value":300})", kJson);  // I8
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400);
  EXPECT_NE(json::parse(r->body)["error"].get<std::string>().find("does not fit"), std::string::npos);
  r = c.Put("/api/v1/slaves/1/objects/0x6060/0", R"({"value":8,)", kJson);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400);
  EXPECT_NE(json::parse(r->body)["error"].get<std::string>().find("not JSON"), std::string::npos);
  r = c.Put("/api/v1/slaves/1/objects/0x6060/0", R"({"value":1E999})", kJson);  // too large for a double
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400);
  EXPECT_NE(json::parse(r->body)["error"].get<std::string>().find("not JSON"), std::string::npos);
  r = c.Put("/api/v1/slaves/1/objects/0x6060/0", R"({"value":8})", "text/plain");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 415);
}

TEST(WebApi, OversizedBodiesAreRefused) {
  WebLine line;
  const std::string big = R"({"kind":"jam","slave":1,"x":")" + std::string(70'000, 'a') + "\"}";
  auto r = line.client().Post("/api/v1/faults", big, kJson);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 413);
  EXPECT_TRUE(json::parse(r->body).contains("error"));
}

// Changes past the bound are 429 with Retry-After and never reach the loop; reads are not bounded.
TEST(WebApi, AFloodOfChangesIsBounded) {
  WebLine line;
  auto c = line.client();
  int limited = 0;
  std::string retry_after, error;
  for (int i = 0; i < 120; ++i) {
    auto r = c.Delete("/api/v1/faults");
    ASSERT_TRUE(r);
    if (r->status == 429) {
      ++limited;
      retry_after = r->get_header_value("Retry-After");
      error = json::parse(r->body)["error"].get<std::string>();
    }
  }
  EXPECT_GT(limited, 0);
  EXPECT_EQ(retry_after, "1");
  EXPECT_NE(error.find("too many requests"), std::string::npos) << error;
  for (int i = 0; i < 120; ++i) {
    auto r = c.Get("/api/v1/faults");
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 200);
  }
}

TEST(WebApi, UnknownEndpointsAre404WithAMessage) {
  WebLine line;
  auto r = line.client().Get("/api/v1/nothing");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 404);
  EXPECT_TRUE(json::parse(r->body).contains("error"));
  r = line.client().Post("/api/v1/line", "{}", kJson);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 404);
}

TEST(WebApi, FaultKindsListEveryKindWithItsFields) {
  WebLine line;
  const json j = line.get("/api/v1/fault-kinds");
  ASSERT_GE(j["kinds"].size(), 25u);
  bool alarm = false;
  for (const json& k : j["kinds"]) {
    if (k["kind"] != "alarm") continue;
    alarm = true;
    std::vector<std::string> names;
    for (const json& f : k["fields"]) names.push_back(f["name"]);
    EXPECT_EQ(names, (std::vector<std::string>{"slave", "code"}));  // one-shot: no duration
  }
  EXPECT_TRUE(alarm);
}

TEST(WebApi, FaultsAreInjectedListedAndCleared) {
  WebLine line;
  auto c = line.client();
  auto r = c.Post("/api/v1/faults", R"({"kind":"jam","slave":1})", kJson);
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 201) << r->body;
  const int id = json::parse(r->body)["id"];
  EXPECT_GT(id, 0);
  const json list = line.get("/api/v1/faults");
  ASSERT_EQ(list["faults"].size(), 1u);
  EXPECT_EQ(list["faults"][0]["kind"], "jam");
  ASSERT_TRUE(eventually([&] { return line.get("/api/v1/line")["faults"].size() == 1; }));
  r = c.Delete(("/api/v1/faults/" + std::to_string(id)).c_str());
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  r = c.Delete(("/api/v1/faults/" + std::to_string(id)).c_str());
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 404);
  EXPECT_TRUE(line.get("/api/v1/faults")["faults"].empty());
}

TEST(WebApi, AFaultAfterADelayIsScheduledThenInjected) {
  WebLine line;
  auto r = line.client().Post("/api/v1/faults", R"({"kind":"jam","slave":2,"after":"100ms"})", kJson);
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 202) << r->body;
  EXPECT_EQ(line.get("/api/v1/faults")["scheduled"].size(), 1u);
  ASSERT_TRUE(eventually([&] { return line.get("/api/v1/faults")["faults"].size() == 1; }));
  EXPECT_TRUE(line.get("/api/v1/faults")["scheduled"].empty());
  r = line.client().Delete("/api/v1/faults");
  ASSERT_TRUE(r);
  EXPECT_EQ(json::parse(r->body)["cleared"], 1);
}

TEST(WebApi, BadFaultsAreRefusedNamingTheField) {
  WebLine line;
  auto c = line.client();
  auto r = c.Post("/api/v1/faults", R"({"kind":"jamm","slave":1})", kJson);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400);
  EXPECT_NE(json::parse(r->body)["error"].get<std::string>().find("jamm"), std::string::npos);
  r = c.Post("/api/v1/faults", R"({"kind":"jam","slave":4})", kJson);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400);
  r = c.Post("/api/v1/faults", R"({"kind":"jam","slave":1,"after":"soon"})", kJson);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400);
  EXPECT_NE(json::parse(r->body)["error"].get<std::string>().find("after"), std::string::npos);
  r = c.Post("/api/v1/faults", "[1,2]", kJson);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400);
}

TEST(WebApi, PlantChangesReachThePlantAndTheLog) {
  WebLine line;
  auto c = line.client();
  auto r = c.Post("/api/v1/slaves/1/plant", R"({"external_load":0.5,"brake":"released"})", kJson);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200) << r->body;
  ASSERT_TRUE(eventually([&] { return !line.get("/api/v1/events?kind=plant_set&slave=1")["events"].empty(); }));
  r = c.Post("/api/v1/slaves/1/plant", R"({"friction":1})", kJson);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400);
  r = c.Post("/api/v1/slaves/1/plant", R"({"brake":"loose"})", kJson);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400);
}

TEST(WebApi, SignalsAreListedAndSet) {
  WebLine line;
  EXPECT_TRUE(line.get("/api/v1/signals")["signals"].empty());  // no network file names any
  auto r = line.client().Put("/api/v1/signals/1.home", R"({"value":1})", kJson);
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  EXPECT_EQ(json::parse(r->body)["signals"][0]["value"], 1);
  r = line.client().Put("/api/v1/signals/nothing", R"({"value":1})", kJson);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400);
}

TEST(WebApi, EventsAreFilteredAndSavedAsCsv) {
  WebLine line;
  (void)line.client().Post("/api/v1/faults", R"({"kind":"jam","slave":3})", kJson);
  ASSERT_TRUE(eventually([&] { return !line.get("/api/v1/events?kind=fault_injected")["events"].empty(); }));
  const json j = line.get("/api/v1/events?kind=fault_injected&slave=3");
  EXPECT_EQ(j["events"][0]["slave"], 3);
  EXPECT_TRUE(line.get("/api/v1/events?kind=fault_injected&slave=2")["events"].empty());
  auto r = line.client().Get("/api/v1/events.csv?kind=fault_injected");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->get_header_value("Content-Type"), "text/csv");
  EXPECT_EQ(r->body.rfind("seq,time_ns,slave,kind,value,previous,text\n", 0), 0u);
  EXPECT_NE(r->body.find(",fault_injected,"), std::string::npos);
}

TEST(WebApi, TheStreamSendsUpdates) {
  WebLine line;
  std::string got;
  httplib::Client c = line.client();
  (void)c.Get("/api/v1/stream", [&](const char* data, std::size_t n) {
    got.append(data, n);
    return got.find("\n\n", got.find("\n\n") + 2) == std::string::npos;  // two updates, then hang up
  });
  ASSERT_EQ(got.rfind("event: update\ndata: ", 0), 0u);
  const json update = json::parse(got.substr(20, got.find("\n\n") - 20));
  EXPECT_EQ(update["line"]["slaves"].size(), 3u);
  EXPECT_TRUE(update.contains("samples"));
  EXPECT_TRUE(update.contains("events"));
}

TEST(WebApi, ThePageAndTheApiDescriptionAreServed) {
  WebLine line;
  auto r = line.client().Get("/");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  EXPECT_NE(r->body.find("<html"), std::string::npos);
  r = line.client().Get("/lib/chart.min.js");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  EXPECT_NE(r->body.find("Chart.js"), std::string::npos);
  const json api = line.get("/api/v1/openapi.json");
  EXPECT_EQ(api["openapi"].get<std::string>().rfind("3.", 0), 0u);
  r = line.client().Get("/../../etc/passwd");
  ASSERT_TRUE(r);
  EXPECT_NE(r->status, 200);
}

TEST(WebApi, ALoopbackServerAnswersOnlyLocalHostNames) {
  WebLine line;
  auto r = line.client().Get("/api/v1/line", {{"Host", "attacker.example:80"}});
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 403);
}

TEST(WebApi, BeyondLoopbackChangesNeedTheToken) {
  WebLine line("0.0.0.0");
  const std::string token = line.server().token();
  ASSERT_EQ(token.size(), 32u);
  EXPECT_NE(line.server().url().find("#token=" + token), std::string::npos);
  EXPECT_EQ(line.get("/api/v1/line")["token_required"], true);  // reading needs none
  auto r = line.client().Post("/api/v1/faults", R"({"kind":"jam","slave":1})", kJson);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 401);
  r = line.client().Post("/api/v1/faults", httplib::Headers{{"Authorization", "Bearer " + std::string(32, '0')}},
                         std::string(R"({"kind":"jam","slave":1})"), kJson);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 401);
  httplib::Client c = line.client();
  c.set_bearer_token_auth(token.c_str());
  r = c.Post("/api/v1/faults", R"({"kind":"jam","slave":1})", kJson);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 201);
}


// The served description and the server agree: every path and method it lists is answered by a
// route of its own (never the catch-all "no endpoint"), and every answer is JSON or the page.
TEST(WebApi, EveryDescribedEndpointExists) {
  WebLine line;
  const nlohmann::json api = line.get("/api/v1/openapi.json");
  ASSERT_TRUE(api.contains("paths"));
  std::size_t checked = 0;
  for (const auto& [path, methods] : api["paths"].items()) {
    std::string p = path;
    for (const auto& [param, value] : std::vector<std::pair<std::string, std::string>>{
             {"{pos}", "1"}, {"{index}", "0x6041"}, {"{sub}", "0"}, {"{id}", "99"}, {"{name}", "1.home"}}) {
      if (const std::size_t at = p.find(param); at != std::string::npos) p.replace(at, param.size(), value);
    }
    for (const auto& [method, spec] : methods.items()) {
      httplib::Client c = line.client();
      if (method == "get" && p == "/api/v1/stream") {
        std::string got;
        (void)c.Get(p.c_str(), [&](const char* data, std::size_t n) {
          got.append(data, n);
          return false;  // one chunk is enough
        });
        EXPECT_EQ(got.rfind("event: update", 0), 0u) << p;
        ++checked;
        continue;
      }
      const auto send = [&]() -> httplib::Result {
        if (method == "put") return c.Put(p.c_str(), R"({"value":1})", "application/json");
        if (method == "post") return c.Post(p.c_str(), "{}", "application/json");
        if (method == "delete") return c.Delete(p.c_str());
        EXPECT_EQ(method, "get") << path;
        return c.Get(p.c_str());
      };
      const httplib::Result r = send();
      ASSERT_TRUE(r) << method << " " << p;
      EXPECT_EQ(r->body.find("no endpoint"), std::string::npos) << method << " " << p << ": " << r->body;
      EXPECT_EQ(r->body.find("no API endpoint"), std::string::npos) << method << " " << p << ": " << r->body;
      EXPECT_LT(r->status, 500) << method << " " << p << ": " << r->body;
      ++checked;
    }
  }
  EXPECT_GE(checked, 20u);
}


TEST(WebApi, AlarmsAreTheProductsTable) {
  WebLine line;
  const nlohmann::json a6b = line.get("/api/v1/slaves/1/alarms");
  bool overload = false;
  for (const nlohmann::json& a : a6b["alarms"]) overload = overload || (a["code"] == "16.0" && a["error_code"] == 0xFF10);
  EXPECT_TRUE(overload);
  const nlohmann::json ds5c1 = line.get("/api/v1/slaves/2/alarms");
  ASSERT_FALSE(ds5c1["alarms"].empty());
  EXPECT_EQ(ds5c1["alarms"][0]["code"].get<std::string>().rfind("E-", 0), 0u);
  auto r = line.client().Get("/api/v1/slaves/0/alarms");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 404);
}

TEST(WebApi, EachSlaveSaysWhereItIsCabled) {
  WebLine line;
  const nlohmann::json j = line.get("/api/v1/line");
  EXPECT_EQ(j["slaves"][0]["parent"], 0);  // the master
  EXPECT_EQ(j["slaves"][1]["parent"], 1);
  EXPECT_EQ(j["slaves"][1]["parent_port"], 1);
  EXPECT_EQ(j["slaves"][2]["parent"], 2);
}

}  // namespace
}  // namespace vdrive::web::test
