// Part 1's page of a line over processes: a later part's own page read into it and its slaves'
// requests forwarded there (PartPages), with two servers in one test standing in for the parts.
#include <gtest/gtest.h>

#include <mutex>
#include <string>

#include "tests/web/web_line.hpp"

namespace vdrive::web::test {
namespace {

using json = nlohmann::json;
constexpr const char* kJson = "application/json";
constexpr const char* kToken = "part-token";

WebServerOptions later_part() {
  WebServerOptions o;
  o.origin = 0;
  o.token = kToken;
  return o;
}

WebServerOptions first_part(int later_port) {
  WebServerOptions o;
  o.origin = 0;
  o.parts = {{2, 1, later_port}};
  o.parts_token = kToken;
  return o;
}

json body_of(const httplib::Result& r) { return r ? json::parse(r->body) : json{}; }

// A line of three over two parts: a6b and ds5c1 in part 1, ds1000a in part 2 behind it.
struct TwoParts {
  WebServerOptions later = later_part();
  WebLine part2{"127.0.0.1", {"ds1000a"}, &later};
  WebServerOptions first = first_part(part2.server().port());
  WebLine part1{"127.0.0.1", {"a6b", "ds5c1"}, &first};
};

TEST(PartPages, PartOnesPageShowsTheWholeLine) {
  TwoParts parts;
  WebLine& part1 = parts.part1;
  WebLine& part2 = parts.part2;
  ASSERT_TRUE(part1.assign_station_addresses(0x1001));
  ASSERT_TRUE(part2.assign_station_addresses(0x1003));
  ASSERT_TRUE(eventually([&] {
    const json l = part1.get("/api/v1/line");
    return l["slaves"].size() == 3 && l["slaves"][2]["address"] == 0x1003 && l["slaves"][2]["drive"].is_object() &&
           l["slaves"][2]["drive"]["state"] != "unknown";
  }));
  const json line = part1.get("/api/v1/line");
  const json& third = line["slaves"][2];
  EXPECT_EQ(third["position"], 3);
  EXPECT_EQ(third["product"], "ds1000a");
  EXPECT_EQ(third["parent"], 2);
  EXPECT_EQ(third["parent_port"], 1);
  EXPECT_EQ(third["answers"], true);
  EXPECT_EQ(third["al_state_name"], "Init");
  EXPECT_EQ(third["drive"]["state"], "Switch on disabled");
  // Its plot points, under its whole-line position.
  ASSERT_TRUE(eventually([&] {
    const json s = part1.get("/api/v1/samples?slave=3");
    return s["axes"].size() == 1 && s["axes"][0]["t"].size() > 2;
  }));
  EXPECT_EQ(part1.get("/api/v1/samples?slave=0x1003")["axes"][0]["slave"], 3);
  EXPECT_EQ(part1.get("/api/v1/samples")["axes"].size(), 3u);
}

TEST(PartPages, ALaterSlavesRequestsGoToItsPart) {
  TwoParts parts;
  WebLine& part1 = parts.part1;
  WebLine& part2 = parts.part2;
  ASSERT_TRUE(part2.assign_station_addresses(0x1003));
  ASSERT_TRUE(eventually([&] { return part1.get("/api/v1/line")["slaves"][2]["address"] == 0x1003; }));

  // Reads: the part's own answer, by position or station address.
  const json identity = part2.get("/api/v1/slaves/1/objects/0x1018/1");
  ASSERT_TRUE(identity.contains("value")) << identity;
  EXPECT_EQ(part1.get("/api/v1/slaves/3/objects/0x1018/1"), identity);
  EXPECT_EQ(part1.get("/api/v1/slaves/0x1003/objects/0x1018/1"), identity);
  EXPECT_EQ(part1.get("/api/v1/slaves/3/alarms"), part2.get("/api/v1/slaves/1/alarms"));
  EXPECT_FALSE(part1.get("/api/v1/slaves/3/alarms")["alarms"].empty());
  const json found = part1.get("/api/v1/slaves/3/objects?q=following%20error");
  EXPECT_EQ(found, part2.get("/api/v1/slaves/1/objects?q=following%20error"));

  // A write the drive refuses: its abort, its error naming the whole-line slave, its event.
  auto r = part1.client().Put("/api/v1/slaves/3/objects/0x6041/0", R"({"value":0})", kJson);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 409);
  const json refused = json::parse(r->body);
  EXPECT_EQ(refused["abort_code"], "0x06010002");
  EXPECT_NE(refused["error"].get<std::string>().find("slave 3"), std::string::npos) << refused;
  ASSERT_TRUE(eventually([&] { return !part1.get("/api/v1/events?kind=od_abort&slave=3")["events"].empty(); }));

  // A plant change reaches the part's plant.
  r = part1.client().Post("/api/v1/slaves/3/plant", R"({"external_load":0.5})", kJson);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200) << r->body;
  ASSERT_TRUE(eventually([&] { return !part1.get("/api/v1/events?kind=plant_set&slave=3")["events"].empty(); }));

  // Beyond the line: part 1 says so itself.
  r = part1.client().Get("/api/v1/slaves/4/alarms");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 404);
}

TEST(PartPages, APartsPageTakesChangesOnlyWithTheRunsToken) {
  const WebServerOptions later = later_part();
  WebLine part2("127.0.0.1", {"ds1000a"}, &later);
  auto r = part2.client().Put("/api/v1/slaves/1/objects/0x6060/0", R"({"value":8})", kJson);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 401);
  httplib::Client c = part2.client();
  c.set_bearer_token_auth(kToken);
  r = c.Put("/api/v1/slaves/1/objects/0x6060/0", R"({"value":8})", kJson);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200) << r->body;
  EXPECT_EQ(part2.get("/api/v1/slaves/1/objects/0x6060/0")["value"], 8) << "reads need no token";
}

TEST(PartPages, FaultsAndSignalsGoThroughTheRunsRouter) {
  const WebServerOptions later = later_part();
  WebLine part2("127.0.0.1", {"ds1000a"}, &later);
  std::mutex m;
  std::vector<std::string> routed;
  WebServerOptions o = first_part(part2.server().port());
  o.route = [&](const control::ControlRequest& r, std::string_view line) {
    const std::lock_guard<std::mutex> lock(m);
    routed.emplace_back(line);
    control::ControlReply reply;
    if (r.op == control::ControlRequest::Op::inject) reply.id = 2;
    return reply;
  };
  WebLine part1("127.0.0.1", {"a6b", "ds5c1"}, &o);
  auto r = part1.client().Post("/api/v1/faults", R"({"kind":"overload","slave":3})", kJson);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 201) << r->body;
  EXPECT_EQ(body_of(r)["id"], 2) << "the run-wide id the router answers";
  r = part1.client().Post("/api/v1/faults", R"({"kind":"overload","slave":4})", kJson);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400) << "no slave 4 in a line of 3";
  EXPECT_NE(body_of(r)["error"].get<std::string>().find("1 to 3"), std::string::npos) << r->body;
  r = part1.client().Delete("/api/v1/faults/2", httplib::Headers{}, "", kJson);
  ASSERT_TRUE(r);
  r = part1.client().Put("/api/v1/signals/door", R"({"value":1})", kJson);
  ASSERT_TRUE(r);
  const auto asked = [&](const std::string& part) {
    const std::lock_guard<std::mutex> lock(m);
    return std::any_of(routed.begin(), routed.end(), [&](const std::string& l) { return l.find(part) != std::string::npos; });
  };
  EXPECT_TRUE(eventually([&] { return asked(R"({"op":"list"})"); })) << "the page's list of active faults too";
  EXPECT_TRUE(asked(R"("op":"inject")") && asked(R"("slave":3)"));
  EXPECT_TRUE(asked(R"({"id":2,"op":"clear"})"));
  EXPECT_TRUE(asked(R"("signal":"door")"));
}

TEST(PartPages, APartThatEndsIsNamedAndItsSlavesMarked) {
  const WebServerOptions later = later_part();
  auto part2 = std::make_unique<WebLine>("127.0.0.1", std::vector<std::string>{"ds1000a"}, &later);
  const WebServerOptions first = first_part(part2->server().port());
  WebLine part1("127.0.0.1", {"a6b", "ds5c1"}, &first);
  ASSERT_TRUE(eventually([&] { return part1.get("/api/v1/line")["slaves"][2]["answers"] == true; }));
  part2.reset();
  ASSERT_TRUE(eventually([&] { return part1.get("/api/v1/line")["slaves"][2]["answers"] == false; }));
  EXPECT_EQ(part1.get("/api/v1/line")["slaves"][2]["al_state_name"], "no answer");
  EXPECT_EQ(part1.get("/api/v1/line")["slaves"][2]["product"], "ds1000a") << "its last view stays";
  const json silent = part1.get("/api/v1/events?kind=part_silent")["events"];
  ASSERT_EQ(silent.size(), 1u);
  EXPECT_NE(silent[0]["text"].get<std::string>().find("part 2 (slave 3) does not answer"), std::string::npos) << silent;
  auto r = part1.client().Get("/api/v1/slaves/3/objects/0x1000/0");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 503);
  EXPECT_NE(json::parse(r->body)["error"].get<std::string>().find("part 2 (slave 3)"), std::string::npos) << r->body;
}

}  // namespace
}  // namespace vdrive::web::test
