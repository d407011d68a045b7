#pragma once
// The vectorized escape-time loop, instantiated by escape_avx2.cpp and escape_avx512.cpp with their Ops.
//
// V vectors of W lanes hold V*W points at once; the iterations of the V vectors are independent, which hides the
// latency of the multiply-add chain. When a lane's point escapes or reaches the cap, its result is written and the
// next point of the batch is loaded into that lane ("refill"), so lanes never idle while work is left. A single
// iteration clock `it` serves every lane: a lane loaded at clock s has run it - s iterations, and reaches the cap at
// its deadline s + max. Each point's arithmetic is the sequence of escape_points.hpp whatever lane it lands in.
#include <cstddef>
#include <cstdint>

#include "escape_points.hpp"

namespace tessera::detail {
namespace {

template <class Ops, int V>
void escape_points_refill(const PointBatch& batch, const IterationLimits& limits) {
  using D = typename Ops::D;
  constexpr int W = Ops::kLanes;
  constexpr int S = V * W;
  constexpr uint64_t kNever = ~uint64_t(0);

  alignas(64) double xs[S], ys[S], yys[S], mags[S], crs[S], cis[S];
  uint64_t deadline[S];
  size_t point[S];
  size_t next = 0;
  uint64_t it = 0;
  int live = 0;

  // Loads the next point that does not escape at n = 0 into slot s, or parks the slot (z = c = 0 never escapes).
  const auto fill = [&](int s) {
    while (next < batch.count) {
      const size_t i = next++;
      const double x = batch.zr[i], y = batch.zi[i];
      const double yy = y * y;
      const double m = __builtin_fma(x, x, yy);
      if (m > limits.bailout2) {
        batch.iterations[i] = 0;
        batch.norm2[i] = m;
        continue;
      }
      xs[s] = x, ys[s] = y, yys[s] = yy, crs[s] = batch.cr[i], cis[s] = batch.ci[i];
      deadline[s] = it + limits.max_iterations;
      point[s] = i;
      ++live;
      return;
    }
    xs[s] = ys[s] = yys[s] = crs[s] = cis[s] = 0;
    deadline[s] = kNever;
  };

  for (int s = 0; s < S; ++s) fill(s);
  uint64_t soonest = kNever;
  for (int s = 0; s < S; ++s) soonest = deadline[s] < soonest ? deadline[s] : soonest;

  D x[V], y[V], yy[V], m[V];
  const D bailout2 = Ops::set1(limits.bailout2);
#pragma GCC unroll 16
  for (int v = 0; v < V; ++v)
    x[v] = Ops::load(xs + v * W), y[v] = Ops::load(ys + v * W), yy[v] = Ops::load(yys + v * W);

  while (live > 0) {
    ++it;
    unsigned escaped[V];
    unsigned any = 0;
#pragma GCC unroll 16
    for (int v = 0; v < V; ++v) {
      const D t = Ops::sub(Ops::load(crs + v * W), yy[v]);
      const D x2 = Ops::add(x[v], x[v]);
      const D xn = Ops::fma(x[v], x[v], t);
      y[v] = Ops::fma(x2, y[v], Ops::load(cis + v * W));
      x[v] = xn;
      yy[v] = Ops::mul(y[v], y[v]);
      m[v] = Ops::fma(x[v], x[v], yy[v]);
      escaped[v] = Ops::greater(m[v], bailout2);
      any |= escaped[v];
    }
    if (any == 0 && it != soonest) continue;

    // Slow path: write the finished points (escaped, or at their deadline), refill their lanes.
    unsigned done[V];
#pragma GCC unroll 16
    for (int v = 0; v < V; ++v) done[v] = escaped[v];
    bool oldest_done = it == soonest;
    if (oldest_done)
      for (int s = 0; s < S; ++s)
        if (deadline[s] == it) done[s / W] |= 1u << (s % W);
#pragma GCC unroll 16
    for (int v = 0; v < V; ++v) {
      if (done[v] == 0) continue;
      Ops::store(xs + v * W, x[v]), Ops::store(ys + v * W, y[v]), Ops::store(yys + v * W, yy[v]);
      Ops::store(mags + v * W, m[v]);
      for (unsigned bits = done[v]; bits != 0; bits &= bits - 1) {
        const int s = v * W + __builtin_ctz(bits);
        const size_t i = point[s];
        batch.iterations[i] = uint32_t(it - (deadline[s] - limits.max_iterations));
        batch.norm2[i] = mags[s];
        oldest_done |= deadline[s] == soonest;
        --live;
        fill(s);
      }
      x[v] = Ops::load(xs + v * W), y[v] = Ops::load(ys + v * W), yy[v] = Ops::load(yys + v * W);
    }
    // Deadlines are handed out in increasing order, so the soonest one only moves when its slot finished.
    if (oldest_done) {
      soonest = kNever;
      for (int s = 0; s < S; ++s) soonest = deadline[s] < soonest ? deadline[s] : soonest;
    }
  }
}

}  // namespace
}  // namespace tessera::detail
