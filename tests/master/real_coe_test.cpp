// The CoE client against the slaves' own CoE firmware (vdrive/firmware/coe) on a line of all
// three products: identity objects agree with the SII, unknown objects abort with the CiA 301
// code, SDO information lists the dictionary and describes its objects.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "master/coe.hpp"
#include "master/master.hpp"
#include "tests/master/virtual_line.hpp"

namespace vdrive::master {
namespace {

class RealCoe : public ::testing::Test {
protected:
  test::VirtualLine line{{"a6b", "ds5c1", "ds1000a"}};
  Master master{line, line.clock()};
  void SetUp() override {
    ASSERT_EQ(master.scan(), 3u);
    ASSERT_TRUE(master.request_state(AlState::PreOp));
    master.set_mailbox_timeout(20'000'000);
  }
};

TEST_F(RealCoe, IdentityObjectMatchesTheSii) {
  for (std::size_t i = 0; i < 3; ++i) {
    SCOPED_TRACE(i);
    SdoClient& sdo = master.sdo(i);
    const SlaveInfo& info = master.slaves()[i].info;
    EXPECT_EQ(sdo.upload_value<std::uint8_t>(0x1018, 0), 4);
    EXPECT_EQ(sdo.upload_value<std::uint32_t>(0x1018, 1), info.vendor_id);
    EXPECT_EQ(sdo.upload_value<std::uint32_t>(0x1018, 2), info.product_code);
  }
}

TEST_F(RealCoe, UnknownObjectAborts) {
  for (std::size_t i = 0; i < 3; ++i) {
    try {
      master.sdo(i).upload(0x5FFE, 0);
      ADD_FAILURE() << "slave " << i << ": no abort";
    } catch (const SdoAbort& e) {
      EXPECT_EQ(e.code(), 0x06020000u) << i;
    }
  }
}

TEST_F(RealCoe, OdListContainsTheIdentityAndIsDescribed) {
  for (std::size_t i = 0; i < 3; ++i) {
    SCOPED_TRACE(i);
    SdoClient& sdo = master.sdo(i);
    const auto list = sdo.od_list();
    EXPECT_GT(list.size(), 20u);
    EXPECT_NE(std::find(list.begin(), list.end(), 0x1018), list.end());
    const ObjectDescription d = sdo.object_description(0x1018);
    EXPECT_EQ(d.index, 0x1018);
    EXPECT_EQ(d.max_subindex, 4);
    EXPECT_FALSE(d.name.empty());
    const EntryDescription e = sdo.entry_description(0x1018, 1);
    EXPECT_EQ(e.bit_length, 32);
  }
}

}  // namespace
}  // namespace vdrive::master
