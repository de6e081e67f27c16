// The `vdrive` command as a user meets it: the built binary run with good and bad arguments;
// exit codes and one-line error messages (docs/cli.md). Serving tests need root (veth, TAP).
#include <gtest/gtest.h>
#include <sched.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <memory>
#include <regex>
#include <string>
#include <vector>

#include "tests/support/child_process.hpp"
#include "tests/support/runtime_test_support.hpp"
#include "vdrive/link/raw_socket_link.hpp"
#include "vdrive/profile/profile_loader.hpp"

#ifndef VDRIVE_BINARY
#error "tests/CMakeLists.txt defines VDRIVE_BINARY as the path of the built vdrive program"
#endif

namespace vdrive::cli {
namespace {

using namespace std::chrono_literals;
using test::ProcessResult;

ProcessResult vdrive(const std::vector<std::string>& args, bool drop_to_nobody = false) {
  return test::run_process(VDRIVE_BINARY, args, drop_to_nobody);
}

// One line, in the documented format.
void expect_one_error_line(const ProcessResult& r, const std::string& must_contain) {
  EXPECT_EQ(r.err.rfind("vdrive: error: ", 0), 0u) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find(must_contain), std::string::npos) << r.err;
}

bool have_product(const std::string& id) {
  const auto known = profile::known_products();
  return std::find(known.begin(), known.end(), id) != known.end();
}

TEST(Cli, VersionPrintsTheVersionAndExitsZero) {
  const auto r = vdrive({"--version"});
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_TRUE(std::regex_search(r.out, std::regex(R"(^vdrive \d+\.\d+\.\d+)"))) << r.out;
  EXPECT_TRUE(r.err.empty());
}

TEST(Cli, HelpExitsZero) {
  const auto r = vdrive({"run", "--help"});
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("--iface"), std::string::npos);
  EXPECT_NE(r.out.find("--drive"), std::string::npos);
}

TEST(Cli, NoSubcommandIsABadArgument) {
  const auto r = vdrive({});
  EXPECT_EQ(r.exit_code, 2);
  expect_one_error_line(r, "no command given");
}

TEST(Cli, UnknownTopLevelOptionIsNamed) {
  const auto r = vdrive({"--bogus"});
  EXPECT_EQ(r.exit_code, 2);
  expect_one_error_line(r, "--bogus");
}

TEST(Cli, UnknownOptionIsNamed) {
  const auto r = vdrive({"run", "--iface", "lo", "--drive", "a6b", "--bogus"});
  EXPECT_EQ(r.exit_code, 2);
  expect_one_error_line(r, "--bogus");
}

TEST(Cli, AnUnknownNetworkNamespaceIsNamed) {
  const auto r = vdrive({"run", "--netns", "vdrive-no-such-ns", "--iface", "x", "--drive", "a6b"});
  EXPECT_EQ(r.exit_code, 2);
  expect_one_error_line(r, "--netns: no network namespace 'vdrive-no-such-ns' (ip netns add vdrive-no-such-ns makes one)");
}

TEST(Cli, ATelemetrySubscriberThatHearsNothingSaysSoAndFails) {
  const auto r = vdrive({"telemetry", "--domain", "229", "--duration", "0.5", "--quiet"});
  EXPECT_EQ(r.exit_code, 1);
  expect_one_error_line(r, "no telemetry heard in domain 229");
}

TEST(Cli, MissingDriveIsNamed) {
  const auto r = vdrive({"run", "--iface", "lo"});
  EXPECT_EQ(r.exit_code, 2);
  expect_one_error_line(r, "--drive");
}

TEST(Cli, MalformedHopDelayIsNamed) {
  auto r = vdrive({"run", "--iface", "lo", "--drive", "a6b", "--hop-delay", "fast"});
  EXPECT_EQ(r.exit_code, 2);
  expect_one_error_line(r, "--hop-delay");
  r = vdrive({"run", "--iface", "lo", "--drive", "a6b", "--hop-delay", "-5"});
  EXPECT_EQ(r.exit_code, 2);
  expect_one_error_line(r, "--hop-delay");
}

TEST(Cli, BadLogLevelIsNamed) {
  const auto r = vdrive({"run", "--iface", "lo", "--drive", "a6b", "--log-level", "loud"});
  EXPECT_EQ(r.exit_code, 2);
  expect_one_error_line(r, "--log-level");
}

TEST(Cli, RtPriorityOutOfRangeIsNamed) {
  for (const char* bad : {"0", "100", "high"}) {
    const auto r = vdrive({"run", "--iface", "lo", "--drive", "a6b", "--rt-priority", bad});
    EXPECT_EQ(r.exit_code, 2) << bad;
    expect_one_error_line(r, "--rt-priority");
  }
}

TEST(Cli, SliceOutOfRangeOrWithSchedFifoIsNamed) {
  for (const char* bad : {"99", "100001", "short"}) {
    const auto r = vdrive({"run", "--iface", "lo", "--drive", "a6b", "--slice-us", bad});
    EXPECT_EQ(r.exit_code, 2) << bad;
    expect_one_error_line(r, "--slice-us");
  }
  const auto r = vdrive({"run", "--iface", "lo", "--drive", "a6b", "--slice-us", "200", "--rt-priority", "10"});
  EXPECT_EQ(r.exit_code, 2);
  expect_one_error_line(r, "--slice-us");
}

TEST(Cli, IfaceAndTapExcludeEachOther) {
  const auto r = vdrive({"run", "--iface", "lo", "--tap", "vdt0", "--drive", "a6b"});
  EXPECT_EQ(r.exit_code, 2);
  expect_one_error_line(r, "--tap");
}

TEST(Cli, RxRingIsForRawSocketsNotTaps) {
  const auto r = vdrive({"run", "--tap", "vdt0", "--rx-ring", "--drive", "a6b"});
  EXPECT_EQ(r.exit_code, 2);
  expect_one_error_line(r, "--rx-ring");
}

TEST(Cli, RunNeedsAnInterfaceOrATap) {
  const auto r = vdrive({"run", "--drive", "a6b"});
  EXPECT_EQ(r.exit_code, 2);
  expect_one_error_line(r, "--iface");
}

TEST(Cli, UnknownProductIsABadArgument) {
  const auto r = vdrive({"run", "--iface", "lo", "--drive", "nosuchdrive"});
  EXPECT_EQ(r.exit_code, 2);
  expect_one_error_line(r, "unknown product 'nosuchdrive'");
}

// --plant counts slaves as every command does, from 1; a station address is the master's to set
// later, so it names no slave at start-up.
TEST(Cli, PlantPositionsCountFromOne) {
  auto r = vdrive({"run", "--iface", "lo", "--drive", "a6b", "--plant", "0:axis.yaml"});
  EXPECT_EQ(r.exit_code, 2);
  expect_one_error_line(r, "--plant '0:axis.yaml': slave 0: positions count from 1");
  r = vdrive({"run", "--iface", "lo", "--drive", "a6b", "--plant", "2:axis.yaml"});
  EXPECT_EQ(r.exit_code, 2);
  expect_one_error_line(r, "--plant '2:axis.yaml': there are 1 drives (positions 1-1)");
  r = vdrive({"run", "--iface", "lo", "--drive", "a6b", "--plant", "0x1001:axis.yaml"});
  EXPECT_EQ(r.exit_code, 2);
  expect_one_error_line(r, "a station address is set by the master when it runs; give the slave's position (1 = first)");
  r = vdrive({"run", "--iface", "lo", "--drive", "a6b", "--plant", "1:/nonexistent-vdrive-plant.yaml"});
  EXPECT_EQ(r.exit_code, 2);
  expect_one_error_line(r, "/nonexistent-vdrive-plant.yaml");  // slave 1 taken: its file is read
}

TEST(Cli, AProductMissingFromTheProfileDirIsABadArgument) {
  for (const char* command : {"od", "sii", "esi"}) {
    std::vector<std::string> args = {command, "--drive", "a6b", "--profile-dir", "/nonexistent-vdrive-profiles"};
    if (std::string(command) == "sii") args.push_back("--hex");
    const auto r = vdrive(args);
    EXPECT_EQ(r.exit_code, 2) << command;
    expect_one_error_line(r, "/nonexistent-vdrive-profiles/a6b/profile.yaml");
  }
}

TEST(Cli, MissingInterfaceExitsThree) {
  if (!have_product("a6b")) GTEST_SKIP() << "profile a6b not in this build yet";
  const auto r = vdrive({"run", "--iface", "vdtnosuch0", "--drive", "a6b"});
  EXPECT_EQ(r.exit_code, 3);
  expect_one_error_line(r, "no interface 'vdtnosuch0'");
}

TEST(Cli, InterfaceDownExitsThree) {
  if (!test::running_as_root()) GTEST_SKIP() << "needs root (veth)";
  if (!have_product("a6b")) GTEST_SKIP() << "profile a6b not in this build yet";
  test::VethPair veth;
  ASSERT_TRUE(veth.ok());
  ASSERT_TRUE(test::run_quiet("ip link set " + veth.b() + " down"));
  const auto r = vdrive({"run", "--iface", veth.b(), "--drive", "a6b"});
  EXPECT_EQ(r.exit_code, 3);
  expect_one_error_line(r, "is down");
}

TEST(Cli, MissingPrivilegesExitFour) {
  if (!test::running_as_root()) GTEST_SKIP() << "drops root to nobody in the child";
  if (!have_product("a6b")) GTEST_SKIP() << "profile a6b not in this build yet";
  const auto r = vdrive({"run", "--iface", "lo", "--drive", "a6b"}, /*drop_to_nobody=*/true);
  ASSERT_NE(r.exit_code, 120) << "could not drop privileges";
  ASSERT_NE(r.exit_code, 127) << "nobody cannot execute " VDRIVE_BINARY;
  EXPECT_EQ(r.exit_code, 4);
  expect_one_error_line(r, "CAP_NET_RAW");
}

TEST(Cli, ListDrivesShowsEveryKnownProductWithItsTitle) {
  const auto r = vdrive({"list-drives"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const auto known = profile::known_products();
  EXPECT_EQ(static_cast<std::size_t>(std::count(r.out.begin(), r.out.end(), '\n')), known.size());
  for (const auto& id : known) {
    const std::string title = profile::load_profile(id).title;
    EXPECT_FALSE(title.empty()) << id;
    EXPECT_TRUE(std::regex_search(r.out, std::regex("(^|\n)" + id + " +" + std::regex_replace(
        title, std::regex(R"([.^$|()\[\]{}*+?\\])"), R"(\$&)") + "\n")))
        << r.out;
  }
}

// ---- serving: a master at the other end of a veth pair / on a TAP device ----------------------

constexpr Nanos kMs = 1'000'000;

// Broadcast read of the ESC type register: every slave on the line increments the counter.
std::uint16_t brd_working_counter(link::Link& master) {
  const auto request = test::ethercat_frame(0x07 /*BRD*/, 0, 0x0000, 2);
  if (!master.send(request)) return 0xFFFF;
  std::array<std::uint8_t, link::kMaxFrame> buf{};
  const std::size_t n = master.receive(buf, 1000 * kMs);
  if (n != request.size()) return 0xFFFF;
  return test::first_wkc({buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(n)});
}

TEST(CliServe, RunAnswersFramesAndExitsZeroOnSigterm) {
  if (!test::running_as_root()) GTEST_SKIP() << "needs root (veth, raw sockets)";
  if (!have_product("a6b") || !have_product("ds5c1") || !have_product("ds1000a")) {
    GTEST_SKIP() << "product profiles not in this build yet";
  }
  test::VethPair veth;
  ASSERT_TRUE(veth.ok());
  test::ChildProcess run(VDRIVE_BINARY, {"run", "--iface", veth.b(), "--drive", "a6b", "--drive",
                                         "ds5c1", "--drive", "ds1000a"});
  ASSERT_TRUE(run.started());
  ASSERT_TRUE(run.wait_for_stderr("serving", 5s)) << run.finish().err;

  link::RawSocketLink master(veth.a());
  EXPECT_EQ(brd_working_counter(master), 3);

  run.signal(SIGTERM);
  const auto r = run.finish(5s);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("stopped: 1 frames in, 1 out"), std::string::npos) << r.err;
}

TEST(CliServe, SigintStopsToo) {
  if (!test::running_as_root()) GTEST_SKIP() << "needs root (veth, raw sockets)";
  if (!have_product("a6b")) GTEST_SKIP() << "profile a6b not in this build yet";
  test::VethPair veth;
  ASSERT_TRUE(veth.ok());
  test::ChildProcess run(VDRIVE_BINARY, {"run", "--iface", veth.b(), "--drive", "a6b"});
  ASSERT_TRUE(run.wait_for_stderr("serving", 5s)) << run.finish().err;
  run.signal(SIGINT);
  EXPECT_EQ(run.finish(5s).exit_code, 0);
}

TEST(CliServe, RemovedInterfaceEndsRunWithExitThree) {
  if (!test::running_as_root()) GTEST_SKIP() << "needs root (veth, raw sockets)";
  if (!have_product("a6b")) GTEST_SKIP() << "profile a6b not in this build yet";
  auto veth = std::make_unique<test::VethPair>();
  ASSERT_TRUE(veth->ok());
  test::ChildProcess run(VDRIVE_BINARY, {"run", "--iface", veth->b(), "--drive", "a6b"});
  ASSERT_TRUE(run.wait_for_stderr("serving", 5s)) << run.finish().err;
  const std::string gone = veth->b();
  veth.reset();  // as if a USB NIC were unplugged
  const auto r = run.finish(5s);
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("vdrive: error: interface '" + gone + "' disappeared"), std::string::npos)
      << r.err;
}

TEST(CliServe, RtPriorityServesUnderSchedFifo) {
  if (!test::running_as_root()) GTEST_SKIP() << "needs root (veth, SCHED_FIFO)";
  if (!have_product("a6b")) GTEST_SKIP() << "profile a6b not in this build yet";
  test::VethPair veth;
  ASSERT_TRUE(veth.ok());
  test::ChildProcess run(VDRIVE_BINARY,
                         {"run", "--iface", veth.b(), "--drive", "a6b", "--rt-priority", "10"});
  ASSERT_TRUE(run.wait_for_stderr("serving", 5s)) << run.finish().err;
  EXPECT_EQ(::sched_getscheduler(run.pid()), SCHED_FIFO);
  sched_param param{};
  ASSERT_EQ(::sched_getparam(run.pid(), &param), 0);
  EXPECT_EQ(param.sched_priority, 10);
  link::RawSocketLink master(veth.a());
  EXPECT_EQ(brd_working_counter(master), 1);
  run.signal(SIGTERM);
  EXPECT_EQ(run.finish(5s).exit_code, 0);
}

TEST(CliServe, TapModeServesTheMasterOnTheTapInterface) {
  if (!test::running_as_root()) GTEST_SKIP() << "needs root (TAP)";
  if (!have_product("a6b")) GTEST_SKIP() << "profile a6b not in this build yet";
  const std::string tap = "vdt" + std::to_string(::getpid()) + "c";
  test::ChildProcess run(VDRIVE_BINARY, {"run", "--tap", tap, "--drive", "a6b", "--drive", "a6b"});
  ASSERT_TRUE(run.wait_for_stderr("serving", 5s)) << run.finish().err;
  {
    link::RawSocketLink master(tap);
    EXPECT_EQ(brd_working_counter(master), 2);
  }
  run.signal(SIGTERM);
  EXPECT_EQ(run.finish(5s).exit_code, 0);
  EXPECT_FALSE(test::run_quiet("ip link show " + tap)) << "the TAP device outlived vdrive";
}

// --tap with --processes: part 1 serves the TAP device, the later parts behind it on veth pairs.
TEST(CliServe, TapModeServesALineOverProcesses) {
  if (!test::running_as_root()) GTEST_SKIP() << "needs root (TAP, veth)";
  if (!have_product("a6b")) GTEST_SKIP() << "profile a6b not in this build yet";
  const std::string tap = "vdt" + std::to_string(::getpid()) + "p";
  test::ChildProcess run(VDRIVE_BINARY, {"run", "--tap", tap, "--processes", "2", "--drive", "a6b", "a6b", "a6b"});
  ASSERT_TRUE(run.wait_for_stderr("serving 2 slave(s) on TAP", 30s)) << run.finish().err;
  {
    link::RawSocketLink master(tap);
    EXPECT_EQ(brd_working_counter(master), 3) << "the BRD passed part 1's two slaves and part 2's one";
  }
  run.signal(SIGTERM);
  const auto done = run.finish(10s);
  EXPECT_EQ(done.exit_code, 0) << done.err;
  EXPECT_NE(done.err.find("part 2 (slave 3) serves"), std::string::npos) << done.err;
  EXPECT_FALSE(test::run_quiet("ip link show " + tap)) << "the TAP device outlived vdrive";
}

}  // namespace
}  // namespace vdrive::cli
