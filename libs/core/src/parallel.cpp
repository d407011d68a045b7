#include "tessera/core/parallel.hpp"

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>

#include <algorithm>

namespace tessera {

struct ThreadLimit::Impl {
  std::unique_ptr<tbb::global_control> control;
};

ThreadLimit::ThreadLimit(int threads) : impl_(std::make_unique<Impl>()) {
  if (threads > 0)
    impl_->control =
        std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, size_t(threads));
}

ThreadLimit::~ThreadLimit() = default;

int thread_count() { return int(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism)); }

void parallel_for(int64_t first, int64_t last, int64_t grain, const std::function<void(int64_t, int64_t)>& body) {
  if (last <= first) return;
  grain = std::max<int64_t>(grain, 1);
  const int64_t chunks = (last - first + grain - 1) / grain;
  tbb::parallel_for(tbb::blocked_range<int64_t>(0, chunks, 1), [&](const tbb::blocked_range<int64_t>& r) {
    for (int64_t c = r.begin(); c != r.end(); ++c) {
      const int64_t b = first + c * grain;
      body(b, std::min(last, b + grain));
    }
  });
}

void parallel_tiles(int width, int height, int tile_size, const std::function<void(const Tile&)>& body) {
  if (width <= 0 || height <= 0) return;
  tile_size = std::max(tile_size, 1);
  const int tiles_x = (width + tile_size - 1) / tile_size;
  const int tiles_y = (height + tile_size - 1) / tile_size;
  parallel_for(0, int64_t(tiles_x) * tiles_y, 1, [&](int64_t b, int64_t e) {
    for (int64_t t = b; t < e; ++t) {
      const int tx = int(t % tiles_x), ty = int(t / tiles_x);
      const Tile tile{tx * tile_size, ty * tile_size, std::min(width, (tx + 1) * tile_size),
                      std::min(height, (ty + 1) * tile_size)};
      body(tile);
    }
  });
}

}  // namespace tessera
