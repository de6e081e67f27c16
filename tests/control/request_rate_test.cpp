// The request bound: a burst at once, then the rate, and how long to wait when over it.
#include "vdrive/control/request_rate.hpp"

#include <gtest/gtest.h>

namespace vdrive::control {
namespace {

TEST(RequestRate, ABurstThenTheRate) {
  RequestRate rate(10.0, 3.0);
  const Nanos t0 = 5'000'000'000;
  EXPECT_TRUE(rate.take_at(t0));
  EXPECT_TRUE(rate.take_at(t0));
  EXPECT_TRUE(rate.take_at(t0));
  Nanos wait = 0;
  EXPECT_FALSE(rate.take_at(t0, &wait));
  EXPECT_EQ(wait, 100'000'000) << "one more after a tenth of a second at 10 a second";
  EXPECT_FALSE(rate.take_at(t0 + 99'000'000));
  EXPECT_TRUE(rate.take_at(t0 + 100'000'000));
  EXPECT_TRUE(rate.take_at(t0 + 10'000'000'000));  // a long pause refills only the burst
  EXPECT_TRUE(rate.take_at(t0 + 10'000'000'000));
  EXPECT_TRUE(rate.take_at(t0 + 10'000'000'000));
  EXPECT_FALSE(rate.take_at(t0 + 10'000'000'000));
}

TEST(RequestRate, TheRefusalSaysTheBoundAndTheWait) {
  const RequestRate rate;
  EXPECT_EQ(rate.refusal(9'200'000), "too many requests: at most 100 a second (50 at once); try again in 10 ms");
}

}  // namespace
}  // namespace vdrive::control
