// `vdrive network --from-eni`: runs the built program on the test bench's ENI; the network file it
// prints reads back as one; a slave nothing matches is a bad argument naming it. `vdrive od` and
// `vdrive sii` take an ESI device where they take a product.
#include <gtest/gtest.h>

#include <string>

#include "tests/support/child_process.hpp"

#ifndef VDRIVE_BINARY
#error "tests/CMakeLists.txt defines VDRIVE_BINARY as the path of the built vdrive program"
#endif

namespace {

using vdrive::test::run_process;

const std::string kProducts = std::string(VDRIVE_SOURCE_DIR) + "/tests/products";

TEST(NetworkCommand, FromEniPrintsTheNetworkFile) {
  const auto r = run_process(VDRIVE_BINARY, {"network", "--from-eni", kProducts + "/networks/bench_eni.xml", "--esi-dir",
                                             kProducts + "/esi"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("slaves:\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("{name: \"Drive 5 (MINAS-A6B MADLT15BF)\", device: \"a6b\", parent: 4, port: 1, product_code: "
                       "0x613C0005, revision: 0x00020000}"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("# slave 2 'Term 2 (EL1008)'"), std::string::npos) << r.out;
}

TEST(NetworkCommand, AnUnmatchedSlaveIsServedFromTheEniAloneWithAWarning) {
  const auto r = run_process(VDRIVE_BINARY, {"network", "--from-eni", kProducts + "/networks/bench_eni.xml"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("vdrive network: warning: slave 1 'Term 1 (EK1100)' (vendor 0x00000002, product 0x044C2C52, "
                       "revision 0x00110000): served from the ENI alone"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.out.find("bench_eni.xml#1001\""), std::string::npos) << r.out;
}

TEST(NetworkCommand, ASlaveTheEniDescribesTooThinlyIsABadArgument) {
  const auto r = run_process(VDRIVE_BINARY, {"network", "--from-eni", kProducts + "/networks/eni_without_sm_address.xml"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("eni_without_sm_address.xml:12: <Sm3>: slave 'Sensor' (vendor 0x00000001, product 0x00000002, "
                       "revision 0x00000001): Inputs without a <StartAddress>"),
            std::string::npos)
      << r.err;
  EXPECT_TRUE(r.out.empty());
}

TEST(NetworkCommand, OdShowsAnEsiDevicesDictionary) {
  const auto r = run_process(VDRIVE_BINARY, {"od", "--drive", kProducts + "/esi/generic_servo.xml", "--index", "0x6080"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("Max motor speed"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("6000"), std::string::npos) << r.out;
}

TEST(NetworkCommand, ABrokenEsiFileIsABadArgumentForSii) {
  const auto r = run_process(VDRIVE_BINARY, {"sii", "--drive", kProducts + "/esi/none.xml", "--hex"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("none.xml: cannot read the ESI file"), std::string::npos) << r.err;
}

}  // namespace
