// A drive that exists only as an ESI file (tests/products/esi/generic_servo.xml, written by hand in
// a configurator's style) is served with the generic CiA 402 personality: the project master scans
// it beside built-in products, takes the line to Op with DC at 1 ms and it follows a csp sine.
#include <gtest/gtest.h>

#include <string>

#include "master/master.hpp"
#include "master/process_data.hpp"
#include "master/op_run.hpp"
#include "tests/master/csp_sine_run.hpp"
#include "tests/master/virtual_line.hpp"

namespace vdrive::master {
namespace {

const std::string kServo = std::string(VDRIVE_TEST_PRODUCTS_DIR) + "/esi/generic_servo.xml";

TEST(EsiDevice, ScansWithTheIdentityAndPdosOfItsFile) {
  test::VirtualLine line({"a6b", kServo + ":0x402:0x10000", "ds5c1"});
  Master master{line, line.clock()};
  ASSERT_EQ(master.scan(), 3u);
  const SlaveInfo& s = master.slaves()[1].info;
  EXPECT_EQ(s.vendor_id, 0x00FFFF01u);
  EXPECT_EQ(s.product_code, 0x00000402u);
  EXPECT_EQ(s.revision, 0x00010000u);
  EXPECT_EQ(s.name, "Generic Servo 402");
  EXPECT_TRUE(s.mailbox_protocols & mailbox_protocol::kCoE);
  master.set_mailbox_timeout(20'000'000);
  ASSERT_TRUE(master.request_state(AlState::PreOp));
  EXPECT_EQ(master.sdo(1).upload_value<std::uint32_t>(0x1000, 0), 0x00020192u);
  EXPECT_EQ(master.sdo(1).upload_value<std::uint16_t>(0x1C12, 1), 0x1600u);
  EXPECT_EQ(master.sdo(1).upload_value<std::uint32_t>(0x6080, 0), 6000u);
}

TEST(EsiDevice, MasterTakesItToOpAndItFollowsInCsp) {
  test::VirtualLine line({kServo});
  test::expect_lone_drive_follows_csp_sine(line);
}

// The file's PDO rules hold: 1600h and 1601h exclude each other, 1A00h is mandatory. An assignment
// against them is refused at PreOp->SafeOp with the ETG code for the direction.
std::uint16_t al_code_after_assigning(std::vector<std::uint16_t> rx, std::vector<std::uint16_t> tx) {
  test::VirtualLine line({kServo});
  Master master{line, line.clock()};
  EXPECT_EQ(master.scan(), 1u);
  OpRunOptions o;
  o.dc = false;
  o.cycles = 10;
  o.mailbox_timeout = 20'000'000;
  o.preop = [&](Master& m) {
    assign_pdos(m.sdo(0), 0x1C12, rx);
    assign_pdos(m.sdo(0), 0x1C13, tx);
  };
  const OpRunResult r = run_to_op(master, o);
  EXPECT_FALSE(r.reached_op);
  EXPECT_NE(r.error.find("last refused with"), std::string::npos) << r.error;
  return master.slaves()[0].refused_code;
}

TEST(EsiDevice, ExcludingPdosAreNotAssignedTogether) {
  EXPECT_EQ(al_code_after_assigning({0x1600, 0x1601}, {0x1A00}), 0x0025);  // invalid output mapping
}

TEST(EsiDevice, AMandatoryPdoMustBeAssigned) {
  EXPECT_EQ(al_code_after_assigning({0x1600}, {}), 0x0024);  // invalid input mapping
}

}  // namespace
}  // namespace vdrive::master
