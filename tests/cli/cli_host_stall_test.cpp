// A host stall of `vdrive run` (docs/reliability.md "Host stalls"): the whole process stopped
// (SIGSTOP) for 80 ms and let go (SIGCONT), as a host that does not run it would. vdrive names the
// stall in its log with what the drive saw, counts it on the status line and in the summary at
// exit, and an alarm that comes right after it says it followed a host stall. Root: a veth pair.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <regex>
#include <string>
#include <thread>

#include "tests/support/child_process.hpp"
#include "tests/support/runtime_test_support.hpp"

namespace vdrive {
namespace {

#ifdef VDRIVE_BINARY
TEST(CliHostStall, AStoppedProcessIsAHostStallAndAnAlarmAfterItSaysSo) {
  using namespace std::chrono_literals;
  if (!test::running_as_root()) GTEST_SKIP() << "needs root (veth, raw sockets)";
  test::VethPair veth;
  ASSERT_TRUE(veth.ok());
  const std::string socket =
      (std::filesystem::temp_directory_path() / ("vdrive-stall-" + std::to_string(::getpid()) + ".sock")).string();
  test::ChildProcess run(VDRIVE_BINARY, {"run", "--iface", veth.b(), "--drive", "a6b", "--status", "--control", socket});
  ASSERT_TRUE(run.wait_for_stderr("status: 1 slave 1:Init", 5s)) << run.finish().err;

  run.signal(SIGSTOP);
  std::this_thread::sleep_for(80ms);
  run.signal(SIGCONT);
  // A fault right after it (well inside the second in which a fault is said to follow a stall).
  const test::ProcessResult injected =
      test::run_process(VDRIVE_BINARY, {"fault", "inject", "--control", socket, "alarm", "--slave", "1", "--code", "81.1"});
  ASSERT_EQ(injected.exit_code, 0) << injected.err;
  EXPECT_TRUE(run.wait_for_stderr("slave 1 a6b: alarm 81.1 Mailbox setting error protection (603Fh FF51h) after a host stall of ", 5s))
      << run.finish().err;
  EXPECT_TRUE(run.wait_for_stderr(", longest ", 5s)) << "the status line counts it\n" << run.finish().err;

  run.signal(SIGTERM);
  const test::ProcessResult r = run.finish();
  EXPECT_EQ(r.exit_code, 0) << r.err;
  // The warning names the stall with what the drive saw; the host may have added stalls of its own.
  std::smatch m;
  bool found = false;
  const std::regex named(R"(host stall ([0-9.]+) ms \(threshold 1\.0 ms\): drive 1 caught up ([0-9]+) control steps)");
  for (auto it = std::sregex_iterator(r.err.begin(), r.err.end(), named); it != std::sregex_iterator(); ++it) {
    if (std::stod((*it)[1].str()) >= 75.0) {
      found = true;
      EXPECT_GE(std::stoi((*it)[2].str()), 75) << "control steps of at most 1 ms in 75 ms";
    }
  }
  EXPECT_TRUE(found) << "no warning of a stall of about 80 ms\n" << r.err;
  EXPECT_TRUE(std::regex_search(r.err, m, std::regex(R"(\| host stalls [1-9][0-9]*, longest [0-9.]+ ms)"))) << r.err;
  EXPECT_TRUE(std::regex_search(r.err, m, std::regex(R"(host stalls: [1-9][0-9]*, longest [0-9.]+ ms \(docs/reliability.md\))"))) << r.err;
  std::filesystem::remove(socket);
}
#endif

}  // namespace
}  // namespace vdrive
