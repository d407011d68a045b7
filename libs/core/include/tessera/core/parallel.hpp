#pragma once
// Parallel loops over index ranges and 2D tiles (oneTBB underneath), and the global thread limit.
//
// Work is split into fixed chunks that do not depend on the thread count, so any per-chunk result (and every
// per-pixel random sequence) is identical for any --threads N.
#include <cstdint>
#include <functional>
#include <memory>

namespace tessera {

/// Caps the number of worker threads for as long as it lives (0 = all cores). Nest-safe: the innermost wins.
class ThreadLimit {
 public:
  explicit ThreadLimit(int threads);
  ~ThreadLimit();
  ThreadLimit(const ThreadLimit&) = delete;
  ThreadLimit& operator=(const ThreadLimit&) = delete;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The number of threads parallel loops use now (the ThreadLimit in force, else the cores).
int thread_count();

/// Calls body(begin, end) over [first, last) split into chunks of at most `grain` indices, in parallel.
void parallel_for(int64_t first, int64_t last, int64_t grain, const std::function<void(int64_t, int64_t)>& body);

/// A rectangle of pixels [x0, x1) x [y0, y1).
struct Tile {
  int x0, y0, x1, y1;
};

/// Calls body(tile) for every tile_size x tile_size tile of a width x height image, in parallel.
void parallel_tiles(int width, int height, int tile_size, const std::function<void(const Tile&)>& body);

}  // namespace tessera
