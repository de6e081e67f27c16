// SpscQueue: order, full/empty, values moved, and one producer + one consumer thread.
#include "vdrive/runtime/spsc_queue.hpp"

#include <gtest/gtest.h>

#include <string>
#include <thread>

namespace vdrive::runtime {
namespace {

TEST(SpscQueue, FifoUntilFullThenRefuses) {
  SpscQueue<int, 3> q;
  EXPECT_TRUE(q.empty());
  EXPECT_FALSE(q.try_pop());
  EXPECT_TRUE(q.try_push(1));
  EXPECT_TRUE(q.try_push(2));
  EXPECT_TRUE(q.try_push(3));
  EXPECT_FALSE(q.try_push(4));
  EXPECT_EQ(*q.try_pop(), 1);
  EXPECT_TRUE(q.try_push(5));  // the freed slot is used again (wraps)
  EXPECT_EQ(*q.try_pop(), 2);
  EXPECT_EQ(*q.try_pop(), 3);
  EXPECT_EQ(*q.try_pop(), 5);
  EXPECT_TRUE(q.empty());
}

TEST(SpscQueue, MovesValuesInAndOut) {
  SpscQueue<std::string, 2> q;
  std::string s(100, 'x');
  ASSERT_TRUE(q.try_push(std::move(s)));
  const std::optional<std::string> out = q.try_pop();
  ASSERT_TRUE(out);
  EXPECT_EQ(*out, std::string(100, 'x'));
}

TEST(SpscQueue, TwoThreadsSeeEveryValueOnceInOrder) {
  constexpr int kCount = 200'000;
  SpscQueue<int, 8> q;
  std::thread producer([&q] {
    for (int i = 0; i < kCount;) {
      int v = i;
      if (q.try_push(std::move(v))) ++i;
    }
  });
  int expected = 0;
  while (expected < kCount) {
    if (const std::optional<int> v = q.try_pop()) {
      ASSERT_EQ(*v, expected);
      ++expected;
    }
  }
  producer.join();
  EXPECT_TRUE(q.empty());
}

}  // namespace
}  // namespace vdrive::runtime
