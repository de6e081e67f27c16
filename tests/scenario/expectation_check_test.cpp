// How expectations decide: at / by / always, events that never happen, conditions.
#include "vdrive/scenario/expectation_check.hpp"

#include <gtest/gtest.h>

namespace vdrive::scenario {
namespace {

constexpr Nanos ms = 1'000'000;

TimePoint at(Nanos t) { TimePoint p; p.delay = t; return p; }
TimePoint on(EventKind e, int slave, Nanos delay) { TimePoint p; p.event = e; p.slave = slave; p.delay = delay; return p; }

Expectation make(Expectation::Timing timing, Condition c) {
  Expectation e;
  e.name = "e";
  e.timing = timing;
  e.condition = c;
  return e;
}

TEST(ScenarioConditions, MaskEqualsRangesAndNear) {
  Condition c;
  c.mask = 0x6F;
  c.equals = 0x27;
  EXPECT_TRUE(holds(c, 0x1637));
  EXPECT_FALSE(holds(c, 0x0621));
  Condition r;
  r.min = -10;
  r.max = 10;
  EXPECT_TRUE(holds(r, -10));
  EXPECT_FALSE(holds(r, 11));
  Condition n;
  n.near = 1000;
  n.tolerance = 20;
  EXPECT_TRUE(holds(n, 980));
  EXPECT_FALSE(holds(n, 1021));
  EXPECT_EQ(describe(c), "& 0x6F == 0x27");
}

TEST(ScenarioExpectations, AtIsDecidedByTheFirstCheckAtItsTime) {
  EventLog events(1);
  Condition c;
  c.equals = 5;
  Expectation e = make(Expectation::Timing::at, c);
  e.when = at(10 * ms);
  ExpectationCheck k(e);
  k.check(9 * ms, 4, events);
  EXPECT_FALSE(k.result().decided);
  k.check(10 * ms, 5, events);
  EXPECT_TRUE(k.result().decided);
  EXPECT_TRUE(k.result().passed);
  k.check(11 * ms, 4, events);
  EXPECT_TRUE(k.result().passed) << "decided once";
}

TEST(ScenarioExpectations, ByPassesAsSoonAsItHoldsAndFailsAfterItsTime) {
  EventLog events(1);
  Condition c;
  c.min = 3;
  Expectation e = make(Expectation::Timing::by, c);
  e.when = at(5 * ms);
  ExpectationCheck pass(e), late(e);
  for (Nanos t = 0; t <= 6 * ms; t += ms) {
    pass.check(t, t / ms, events);
    late.check(t, t >= 6 * ms ? 9 : 0, events);
  }
  EXPECT_TRUE(pass.result().passed);
  EXPECT_EQ(pass.result().time, 3 * ms);
  EXPECT_FALSE(late.result().passed);
  EXPECT_NE(late.result().message.find("did not hold by 5 ms"), std::string::npos) << late.result().message;
}

TEST(ScenarioExpectations, AlwaysFailsAtTheFirstBreachInsideItsWindow) {
  EventLog events(1);
  Condition c;
  c.equals = 1;
  Expectation e = make(Expectation::Timing::always, c);
  e.from = at(2 * ms);
  e.until = at(4 * ms);
  ExpectationCheck outside(e), inside(e);
  for (Nanos t = 0; t <= 6 * ms; t += ms) {
    outside.check(t, (t < 2 * ms || t > 4 * ms) ? 0 : 1, events);
    inside.check(t, t == 3 * ms ? 0 : 1, events);
  }
  outside.finish(6 * ms, events);
  inside.finish(6 * ms, events);
  EXPECT_TRUE(outside.result().passed) << outside.result().message;
  EXPECT_EQ(outside.result().message, "held over 3 checks");
  EXPECT_FALSE(inside.result().passed);
  EXPECT_EQ(inside.result().time, 3 * ms);
}

TEST(ScenarioExpectations, WaitingForAnEventThatNeverComesFails) {
  EventLog events(2);
  Condition c;
  c.equals = 0;
  Expectation e = make(Expectation::Timing::at, c);
  e.when = on(EventKind::fault, 2, 10 * ms);
  ExpectationCheck k(e);
  k.check(5 * ms, 0, events);
  k.finish(100 * ms, events);
  EXPECT_FALSE(k.result().passed);
  EXPECT_EQ(k.result().message, "never checked: 10 ms after fault of slave 2 did not happen");
}

TEST(ScenarioEvents, StatuswordEdgesAndTargetReachedAfterASetPoint) {
  EventLog events(1);
  events.statusword(1, 0x0637, 1 * ms);  // enabled with bit 10 already up
  events.set_point_given(1);
  events.statusword(1, 0x0237, 2 * ms);  // moving
  events.statusword(1, 0x0637, 3 * ms);  // reached
  events.statusword(1, 0x0618, 4 * ms);  // fault
  EXPECT_EQ(events.resolve(on(EventKind::enabled, 1, 0)), 1 * ms);
  EXPECT_EQ(events.resolve(on(EventKind::target_reached, 1, 1 * ms)), 4 * ms);
  EXPECT_EQ(events.resolve(on(EventKind::fault, 1, 0)), 4 * ms);
  EXPECT_FALSE(events.resolve(on(EventKind::op, 0, 0)));
  events.all_in_state(AlTarget::op, 7 * ms);
  events.all_in_state(AlTarget::op, 9 * ms);
  EXPECT_EQ(events.resolve(on(EventKind::op, 0, 0)), 7 * ms) << "the first time counts";
}

}  // namespace
}  // namespace vdrive::scenario
