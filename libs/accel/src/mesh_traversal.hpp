#pragma once
// The wide-BVH traversal of MeshAccel, one template for both widths: included by mesh_accel.cpp (4 wide, SSE, the
// x86-64 baseline) and mesh_accel_avx2.cpp (8 wide, compiled for AVX2). No floating-point contraction in either, so
// both compute bit-identical triangle results (the same operations in the same order as a scalar Moller-Trumbore).
#include <immintrin.h>

#include <cmath>
#include <cstdint>

#include "tessera/accel/mesh_accel.hpp"

namespace tessera::mesh_traversal {

/// The result of a nearest-hit traversal: the block and lane of the nearest triangle and its barycentrics.
struct Nearest {
  int block = -1, lane = 0;
  float b1 = 0, b2 = 0;
};

/// The entry points: 4 wide with SSE (mesh_accel.cpp), 8 wide with AVX2 (mesh_accel_avx2.cpp).
bool intersect4(const MeshAccel::WideNode<4>* nodes, const MeshAccel::TriangleBlock* blocks, int32_t root, Ray& ray,
                Nearest& nearest, TraversalStats* stats);
bool occluded4(const MeshAccel::WideNode<4>* nodes, const MeshAccel::TriangleBlock* blocks, int32_t root, Ray& ray);
bool intersect8(const MeshAccel::WideNode<8>* nodes, const MeshAccel::TriangleBlock* blocks, int32_t root, Ray& ray,
                Nearest& nearest, TraversalStats* stats);
bool occluded8(const MeshAccel::WideNode<8>* nodes, const MeshAccel::TriangleBlock* blocks, int32_t root, Ray& ray);

// Everything below is compiled once per including file (an unnamed namespace), so the AVX2 file's copies never replace
// the baseline file's at link time.
namespace {

typedef float v4f __attribute__((vector_size(16)));
typedef int32_t v4i __attribute__((vector_size(16)));

inline v4f splat4(float x) { return v4f{x, x, x, x}; }
inline int mask_of(v4i m) { return _mm_movemask_ps(reinterpret_cast<__m128>(m)); }

/// A ray's origin and direction, splatted.
struct RayLanes {
  v4f ox, oy, oz, dx, dy, dz;
  explicit RayLanes(const Ray& r)
      : ox(splat4(r.origin.x)), oy(splat4(r.origin.y)), oz(splat4(r.origin.z)), dx(splat4(r.dir.x)),
        dy(splat4(r.dir.y)), dz(splat4(r.dir.z)) {}
};

/// Four triangles against one ray (Moller-Trumbore, operation by operation as a scalar float Moller-Trumbore with glm
/// cross and dot: the same rounding). Returns the mask of lanes that hit with t in [tmin, tmax] and their t, b1, b2.
inline int hit_block(const MeshAccel::TriangleBlock& b, const RayLanes& r, float tmin, float tmax, v4f& t, v4f& b1,
                     v4f& b2) {
  const auto row = [](const float (&v)[4]) { return *reinterpret_cast<const v4f*>(v); };
  const v4f e1x = row(b.e1[0]), e1y = row(b.e1[1]), e1z = row(b.e1[2]);
  const v4f e2x = row(b.e2[0]), e2y = row(b.e2[1]), e2z = row(b.e2[2]);
  // p = dir x e2, det = e1 . p
  const v4f px = r.dy * e2z - e2y * r.dz, py = r.dz * e2x - e2z * r.dx, pz = r.dx * e2y - e2x * r.dy;
  const v4f det = e1x * px + e1y * py + e1z * pz;
  const v4f inv = splat4(1.0f) / det;
  const v4f tvx = r.ox - row(b.v0[0]), tvy = r.oy - row(b.v0[1]), tvz = r.oz - row(b.v0[2]);
  b1 = (tvx * px + tvy * py + tvz * pz) * inv;
  // q = tv x e1
  const v4f qx = tvy * e1z - e1y * tvz, qy = tvz * e1x - e1z * tvx, qz = tvx * e1y - e1x * tvy;
  b2 = (r.dx * qx + r.dy * qy + r.dz * qz) * inv;
  t = (e2x * qx + e2y * qy + e2z * qz) * inv;
  const v4f zero = splat4(0.0f), one = splat4(1.0f);
  // The scalar kernel's rejections, negated literally (a NaN passes a rejection just as it does there).
  const v4i ok = (det != zero) & ~(b1 < zero) & ~(b1 > one) & ~(b2 < zero) & ~(b1 + b2 > one) & (t >= splat4(tmin)) &
                 (t <= splat4(tmax));
  return mask_of(ok);
}

/// The SIMD types of one node width.
template <int W>
struct Lanes;
template <>
struct Lanes<4> {
  typedef float vf __attribute__((vector_size(16)));
  typedef int32_t vi __attribute__((vector_size(16)));
  static int mask(vi m) { return _mm_movemask_ps(reinterpret_cast<__m128>(m)); }
};
template <>
struct Lanes<8> {
  typedef float vf __attribute__((vector_size(32)));
  typedef int32_t vi __attribute__((vector_size(32)));
#ifdef __AVX__
  static int mask(vi m) { return _mm256_movemask_ps(reinterpret_cast<__m256>(m)); }
#endif
};

/// The traversal: nodes' children tested at once, the hit ones visited nearest entry first (the rest on a stack with
/// their entry distances, skipped when popped beyond the current nearest hit). Nearest hit (AnyHit false: fills
/// nearest, shrinks ray.tmax) or any hit (AnyHit true: returns at the first); Stats counts into stats.
template <int W, bool AnyHit, bool Stats>
bool traverse(const MeshAccel::WideNode<W>* nodes, const MeshAccel::TriangleBlock* blocks, int32_t root, Ray& ray,
              Nearest* nearest, TraversalStats* stats) {
  using vf = typename Lanes<W>::vf;
  const auto splat = [](float x) {
    vf v;
    for (int i = 0; i < W; ++i) v[i] = x;
    return v;
  };
  // Near planes by the direction's sign bit (so -0 counts as negative, as 1 / -0 = -inf); far distances enlarged by
  // 2 gamma(3) (pbrt's conservative rounding), so a ray grazing a box edge is never lost.
  const float inv[3] = {1.0f / ray.dir.x, 1.0f / ray.dir.y, 1.0f / ray.dir.z};
  const int near[3] = {std::signbit(ray.dir.x) ? 3 : 0, std::signbit(ray.dir.y) ? 4 : 1, std::signbit(ray.dir.z) ? 5 : 2};
  const int far[3] = {(near[0] + 3) % 6, (near[1] + 3) % 6, (near[2] + 3) % 6};
  const vf ox = splat(ray.origin.x), oy = splat(ray.origin.y), oz = splat(ray.origin.z);
  const vf ix = splat(inv[0]), iy = splat(inv[1]), iz = splat(inv[2]);
  const vf fx = splat(inv[0] * RayBoxTest::kRobust), fy = splat(inv[1] * RayBoxTest::kRobust),
           fz = splat(inv[2] * RayBoxTest::kRobust);
  const vf tmin = splat(ray.tmin);
  const RayLanes lanes(ray);

  // Children that go on the stack are fetched at once (as Embree does): most are popped later, and their misses then
  // overlap the work on the nearer subtree instead of following it (about 10% more incoherent rays on a 1M mesh).
  const auto prefetch = [&](int32_t ref) {
    const char* p = ref >= 0 ? reinterpret_cast<const char*>(nodes + ref)
                             : reinterpret_cast<const char*>(blocks + (~uint32_t(ref) >> 5));
    const int bytes = ref >= 0 ? int(sizeof(MeshAccel::WideNode<W>)) : int(sizeof(MeshAccel::TriangleBlock));
    for (int line = 0; line < bytes; line += 64) _mm_prefetch(p + line, _MM_HINT_T0);
  };
  struct Entry {
    int32_t ref;
    float dist;
  };
  Entry stack[Bvh::kMaxDepth * W];
  int sp = 0;
  int32_t cur = root;
  bool hit = false;
  for (;;) {
    // Descend through interior nodes until a leaf is reached or no child is hit.
    bool leaf = true;
    while (cur >= 0) {
      const MeshAccel::WideNode<W>& n = nodes[cur];
      // The children's line is needed only once the box test is done: fetch it with the boxes, not after them.
      _mm_prefetch(reinterpret_cast<const char*>(n.child), _MM_HINT_T0);
      if constexpr (Stats) ++stats->nodes;
      const auto row = [&n](int r) { return *reinterpret_cast<const vf*>(n.box[r]); };
      // max(a, b) as a > b ? a : b: a NaN (0 * inf, origin on a slab plane of a parallel ray) leaves b.
      vf t0 = (row(near[0]) - ox) * ix, tn = t0 > tmin ? t0 : tmin;
      t0 = (row(near[1]) - oy) * iy, tn = t0 > tn ? t0 : tn;
      t0 = (row(near[2]) - oz) * iz, tn = t0 > tn ? t0 : tn;
      const vf tmax = splat(ray.tmax);
      vf t1 = (row(far[0]) - ox) * fx, tf = t1 < tmax ? t1 : tmax;
      t1 = (row(far[1]) - oy) * fy, tf = t1 < tf ? t1 : tf;
      t1 = (row(far[2]) - oz) * fz, tf = t1 < tf ? t1 : tf;
      unsigned mask = unsigned(Lanes<W>::mask(tn <= tf));
      if (mask == 0) {
        leaf = false;
        break;
      }
      const int a = __builtin_ctz(mask);
      mask &= mask - 1;
      if (mask == 0) {
        cur = n.child[a];
        continue;
      }
      const int b = __builtin_ctz(mask);
      mask &= mask - 1;
      if (mask == 0) {
        // Two: the nearer now, the other on the stack.
        prefetch(n.child[a]);
        prefetch(n.child[b]);
        if (tn[a] <= tn[b]) {
          stack[sp++] = Entry{n.child[b], tn[b]};
          cur = n.child[a];
        } else {
          stack[sp++] = Entry{n.child[a], tn[a]};
          cur = n.child[b];
        }
        continue;
      }
      // Three or more: push all, sorted so that the nearest is on top (insertion sort; ties keep lane order).
      const int base = sp;
      stack[sp++] = Entry{n.child[a], tn[a]};
      stack[sp++] = Entry{n.child[b], tn[b]};
      do {
        const int c = __builtin_ctz(mask);
        mask &= mask - 1;
        stack[sp++] = Entry{n.child[c], tn[c]};
      } while (mask);
      for (int i = base; i < sp; ++i) prefetch(stack[i].ref);
      for (int i = base + 1; i < sp; ++i) {
        const Entry e = stack[i];
        int j = i;
        for (; j > base && stack[j - 1].dist < e.dist; --j) stack[j] = stack[j - 1];
        stack[j] = e;
      }
      cur = stack[--sp].ref;
    }
    if (leaf) {
      const uint32_t code = ~uint32_t(cur);
      const int first = int(code >> 5), count = int(code & 31) + 1;
      for (int k = first; k < first + count; ++k) {
        v4f t, b1, b2;
        int m = hit_block(blocks[k], lanes, ray.tmin, ray.tmax, t, b1, b2);
        if constexpr (Stats) {
          const v4i used = *reinterpret_cast<const v4i*>(blocks[k].index) >= v4i{0, 0, 0, 0};
          stats->prims += __builtin_popcount(unsigned(mask_of(used)));
        }
        if (m == 0) continue;
        if constexpr (AnyHit) {
          return true;
        } else {
          // The nearest lane; among equal t the last, as the scalar loop that accepts t <= tmax would keep.
          float best = ray.tmax;
          int lane = 0;
          for (; m; m &= m - 1) {
            const int l = __builtin_ctz(unsigned(m));
            if (t[l] <= best) {
              best = t[l];
              lane = l;
            }
          }
          ray.tmax = best;
          *nearest = Nearest{k, lane, b1[lane], b2[lane]};
          hit = true;
        }
      }
    }
    // Pop the nearest pending subtree that may still hold a nearer hit.
    do {
      if (sp == 0) return hit;
      --sp;
    } while (stack[sp].dist > ray.tmax);
    cur = stack[sp].ref;
  }
}

/// The nearest hit, with or without counting (two instantiations, so the counting costs nothing when off).
template <int W, class Node>
bool nearest_hit(const Node* nodes, const MeshAccel::TriangleBlock* blocks, int32_t root, Ray& ray, Nearest& nearest,
                 TraversalStats* stats) {
  return stats ? traverse<W, false, true>(nodes, blocks, root, ray, &nearest, stats)
               : traverse<W, false, false>(nodes, blocks, root, ray, &nearest, nullptr);
}

}  // namespace
}  // namespace tessera::mesh_traversal
