// `vdrive fault` as a user meets it without a server: the catalogue, and every argument error or
// missing server as one line with the documented exit code (docs/cli.md "Runtime control").
// Serving with faults is tests/integration/fault_control.sh (root).
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "tests/support/child_process.hpp"
#include "vdrive/fault/fault_spec.hpp"

namespace vdrive::cli {
namespace {

test::ProcessResult vdrive(const std::vector<std::string>& args) { return test::run_process(VDRIVE_BINARY, args, false); }

void expect_one_error_line(const test::ProcessResult& r, int code, const std::string& must_contain) {
  EXPECT_EQ(r.exit_code, code) << r.err;
  EXPECT_EQ(r.err.rfind("vdrive: error: ", 0), 0u) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find(must_contain), std::string::npos) << r.err;
}

TEST(CliFault, KindsListsTheWholeCatalogue) {
  const auto r = vdrive({"fault", "kinds"});
  EXPECT_EQ(r.exit_code, 0);
  for (const fault::FaultKindInfo& i : fault::fault_catalogue())
    EXPECT_NE(r.out.find(std::string(i.name) + " "), std::string::npos) << i.name;
}

TEST(CliFault, NoServerNamesTheSocketPath) {
  expect_one_error_line(vdrive({"fault", "list", "--control", "/tmp/vdrive-no-such-dir/x.sock"}), 1,
                        "/tmp/vdrive-no-such-dir/x.sock");
  expect_one_error_line(vdrive({"fault", "list", "--iface", "vdt-nothing"}), 1, "vdt-nothing.sock");
}

TEST(CliFault, ArgumentErrorsAreExitTwo) {
  expect_one_error_line(vdrive({"fault", "list"}), 2, "--iface");
  expect_one_error_line(vdrive({"fault", "inject", "--iface", "x"}), 2, "kind");
  expect_one_error_line(vdrive({"fault", "clear", "--iface", "x"}), 2, "ID or --all");
  expect_one_error_line(vdrive({"fault", "clear", "--iface", "x", "3", "--all"}), 2, "ID or --all");
  expect_one_error_line(vdrive({"fault", "inject", "--iface", "x", "drop", "--probability", "lots"}), 2, "--probability");
  expect_one_error_line(vdrive({"fault"}), 2, "subcommand");
}

}  // namespace
}  // namespace vdrive::cli
