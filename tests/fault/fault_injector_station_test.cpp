// A fault on a slave named by its station address lands on the slave the master gave that address,
// found when the fault starts; an address no slave has is refused naming the ones there are.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "ethercat/registers.hpp"
#include "tests/support/station_addresses.hpp"
#include "vdrive/fault/fault_injector.hpp"
#include "vdrive/network/network.hpp"

namespace vdrive::fault {
namespace {

class FaultByAddress : public ::testing::Test {
protected:
  void set_addresses(std::uint16_t first) {
    clock_.advance(100'000);
    ASSERT_TRUE(test::assign_station_addresses(net_, clock_.now(), first));
  }
  FaultSpec overload_at(std::uint16_t station) {
    FaultSpec s;
    s.kind = FaultKind::overload;
    s.station = station;
    return s;
  }

  VirtualClock clock_{1'000'000};
  network::Network net_{std::vector<std::string>{"a6b", "ds5c1", "ds1000a"}, clock_};
  FaultInjector injector_{net_, nullptr};
};

TEST_F(FaultByAddress, TheAddressNamesTheSlaveTheMasterGaveIt) {
  set_addresses(0x2001);
  const int id = injector_.inject(overload_at(0x2003), clock_.now());
  ASSERT_EQ(injector_.active().size(), 1u);
  EXPECT_EQ(injector_.active()[0].id, id);
  EXPECT_EQ(injector_.active()[0].spec.slave, 3);
  EXPECT_EQ(describe(injector_.active()[0].spec), "overload slave 3");
  EXPECT_EQ(describe(overload_at(0x2003)), "overload slave 0x2003");
}

TEST_F(FaultByAddress, AnAddressNoSlaveHasIsRefused) {
  set_addresses(0x1001);
  try {
    injector_.inject(overload_at(0x1009), clock_.now());
    ADD_FAILURE() << "injected on 0x1009";
  } catch (const FaultError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("no slave has station address 0x1009 (the line has 0x1001, 0x1002, 0x1003)"));
  }
  EXPECT_TRUE(injector_.active().empty());
}

}  // namespace
}  // namespace vdrive::fault
