#include "tessera/core/parallel.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <vector>

namespace tessera {
namespace {

TEST(Parallel, ForCoversEveryIndexOnce) {
  std::vector<std::atomic<int>> hits(10007);
  parallel_for(0, 10007, 64, [&](int64_t b, int64_t e) {
    for (int64_t i = b; i < e; ++i) hits[size_t(i)]++;
  });
  for (auto& h : hits) EXPECT_EQ(h.load(), 1);
}

TEST(Parallel, TilesCoverImageOnce) {
  const int w = 103, h = 71;
  std::vector<std::atomic<int>> hits(size_t(w * h));
  parallel_tiles(w, h, 16, [&](const Tile& t) {
    for (int y = t.y0; y < t.y1; ++y)
      for (int x = t.x0; x < t.x1; ++x) hits[size_t(y * w + x)]++;
  });
  for (auto& v : hits) EXPECT_EQ(v.load(), 1);
}

TEST(Parallel, ThreadLimitCapsAndRestores) {
  const int before = thread_count();
  {
    ThreadLimit limit(1);
    EXPECT_EQ(thread_count(), 1);
  }
  EXPECT_EQ(thread_count(), before);
}

TEST(Parallel, EmptyRangesDoNothing) {
  int calls = 0;
  parallel_for(5, 5, 1, [&](int64_t, int64_t) { ++calls; });
  parallel_tiles(0, 10, 4, [&](const Tile&) { ++calls; });
  EXPECT_EQ(calls, 0);
}

}  // namespace
}  // namespace tessera
