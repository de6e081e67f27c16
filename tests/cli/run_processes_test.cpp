// `vdrive run --processes N` and `--next-iface`: the errors a user gets for what cannot be split
// or cabled on. Serving over several processes is tested end to end by integration.split_line
// and integration.two_hosts.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tests/support/child_process.hpp"

#ifndef VDRIVE_BINARY
#error "tests/CMakeLists.txt defines VDRIVE_BINARY as the path of the built vdrive program"
#endif

namespace vdrive::cli {
namespace {

test::ProcessResult vdrive(const std::vector<std::string>& args) { return test::run_process(VDRIVE_BINARY, args, false); }

TEST(RunProcesses, TheCommandNamesWhatCannotBeSplit) {
  auto r = vdrive({"run", "--iface", "lo", "--processes", "3", "--drive", "a6b", "ds5c1"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--processes 3: the line has 2 slave(s); give 1 to 2"), std::string::npos) << r.err;
  r = vdrive({"run", "--iface", "lo", "--processes", "0", "--drive", "a6b"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--processes"), std::string::npos) << r.err;
  r = vdrive({"run", "--iface", "lo", "--processes", "2", "--drive", "a6b", "nosuchdrive"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("nosuchdrive"), std::string::npos) << r.err;
}

TEST(RunProcesses, TheOnwardInterfaceCannotBeTheMastersOwn) {
  const auto r = vdrive({"run", "--iface", "lo", "--next-iface", "lo", "--drive", "a6b"});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("--next-iface lo: the master is on that interface already"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace vdrive::cli
