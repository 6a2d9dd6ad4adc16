// TaskSystem: parallelFor visits every index once; invoke runs both functions, side by side when
// there are threads, and the first may run a parallelFor of its own meanwhile.
#include "throng/core/parallel.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <vector>

namespace throng::core {
namespace {

TEST(TaskSystem, ParallelForVisitsEveryIndexOnce) {
  for (const int threads : {1, 2, 4}) {
    const TaskSystem tasks(threads);
    std::vector<int> seen(1000, 0);
    tasks.parallelFor(seen.size(), 7, [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) ++seen[i];
    });
    for (std::size_t i = 0; i < seen.size(); ++i) ASSERT_EQ(seen[i], 1) << "index " << i << ", " << threads << " threads";
  }
}

TEST(TaskSystem, InvokeRunsBothAndTheFirstMayLoopInParallel) {
  for (const int threads : {1, 2, 4}) {
    const TaskSystem tasks(threads);
    std::vector<int> seen(5000, 0);
    std::atomic<int> second{0};
    tasks.invoke(
        [&] {
          tasks.parallelFor(seen.size(), 64, [&](std::size_t begin, std::size_t end) {
            for (std::size_t i = begin; i < end; ++i) seen[i] += static_cast<int>(i % 3) + 1;
          });
        },
        [&] { second.fetch_add(1); });
    EXPECT_EQ(second.load(), 1) << threads << " threads";
    for (std::size_t i = 0; i < seen.size(); ++i) ASSERT_EQ(seen[i], static_cast<int>(i % 3) + 1) << "index " << i;
  }
}

TEST(TaskSystem, InvokeOnOneThreadRunsTheFirstThenTheSecond) {
  const TaskSystem tasks(1);
  std::vector<int> order;
  tasks.invoke([&] { order.push_back(1); }, [&] { order.push_back(2); });
  EXPECT_EQ(order, (std::vector<int>{1, 2}));
}

}  // namespace
}  // namespace throng::core
