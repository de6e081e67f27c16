// Part 1 of `vdrive run --processes`: its injector serves its own slaves, and a fault for a slave
// that a later part serves is refused saying so, not as a slave the line lacks.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tests/support/station_addresses.hpp"
#include "vdrive/fault/fault_injector.hpp"
#include "vdrive/network/network.hpp"

namespace vdrive::fault {
namespace {

using ::testing::HasSubstr;

class LaterSlaves : public ::testing::Test {
protected:
  std::string refusal(const FaultSpec& spec) {
    try {
      injector_.inject(spec, clock_.now());
    } catch (const FaultError& e) {
      return e.what();
    }
    return "injected";
  }
  static FaultSpec at(FaultKind kind, int slave) {
    FaultSpec s;
    s.kind = kind;
    s.slave = slave;
    return s;
  }

  VirtualClock clock_{1'000'000};
  network::Network net_{std::vector<std::string>{"a6b", "ds5c1"}, clock_};  // slaves 1-2 of 3
  FaultInjector injector_{net_, nullptr};
};

TEST_F(LaterSlaves, AFaultForALaterPartsSlaveSaysWhereItIs) {
  injector_.set_later_slaves(1);
  EXPECT_THAT(refusal(at(FaultKind::overload, 3)),
              HasSubstr("overload slave 3: slave 3 is served by another process of this run (--processes); faults reach this "
                        "process's slaves, 1 to 2"));
  EXPECT_THAT(refusal(at(FaultKind::link_down, 3)), HasSubstr("slave 3 is served by another process of this run"));
  EXPECT_THAT(refusal(at(FaultKind::overload, 4)), HasSubstr("no slave 4 (the line has 3)"));
  EXPECT_THAT(refusal(at(FaultKind::link_down, 4)), HasSubstr("the network has cables into slaves 1..3"));
  EXPECT_EQ(refusal(at(FaultKind::overload, 2)), "injected");
  EXPECT_EQ(injector_.active().size(), 1u);
}

TEST_F(LaterSlaves, AnAddressNotHereMayBeInALaterPart) {
  injector_.set_later_slaves(1);
  clock_.advance(100'000);
  ASSERT_TRUE(test::assign_station_addresses(net_, clock_.now(), 0x1001));
  FaultSpec s = at(FaultKind::overload, 0);
  s.station = 0x1003;
  EXPECT_THAT(refusal(s), HasSubstr("no slave has station address 0x1003 (the line has 0x1001, 0x1002); slaves after 2 are "
                                    "served by other processes of this run, whose addresses are not known here"));
}

TEST_F(LaterSlaves, WithoutLaterPartsTheLineEndsHere) {
  EXPECT_THAT(refusal(at(FaultKind::overload, 3)), HasSubstr("no slave 3 (the line has 2)"));
  EXPECT_THAT(refusal(at(FaultKind::link_down, 3)), HasSubstr("the network has cables into slaves 1..2"));
}

}  // namespace
}  // namespace vdrive::fault
