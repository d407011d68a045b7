// The pipeline's setup: clipping, triangle setup, binning and painter's order, the parts that do not depend on the
// shaders (the raster thread that runs them is in pipeline_schedule.cpp), and the fragment operations the templates
// call (stencil, blending).
#include <fmt/format.h>
#include <immintrin.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <utility>

#include "tessera/raster3d/pipeline.hpp"

namespace tessera::raster3d::detail {
namespace {

constexpr int kMaxStride = 4 + kMaxVaryings;
constexpr int kMaxClipVertices = 3 + 6;  // each of the six planes adds at most one vertex to a convex polygon

// Signed distance of a clip-space point to plane p of the clip volume -w <= x, y, z <= w (inside when >= 0), the
// planes in the order Mesa's clipper takes them (draw_context.c): x <= w, -w <= x, y <= w, -w <= y, -w <= z, z <= w.
inline float plane_distance(const float* v, int p) {
  const float c = v[p >> 1];
  return ((p & 1) != (p >> 1 == 2)) ? v[3] + c : v[3] - c;
}

inline bool finite_position(const float* v) {
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]) && std::isfinite(v[3]);
}

constexpr unsigned kNotFinite = 1u << 6;  // PreparedVertex::outcode of a NaN or infinite position

inline unsigned outcode(const float* v) {
  unsigned code = 0;
  for (int p = 0; p < 6; ++p)
    if (plane_distance(v, p) < 0) code |= 1u << p;
  return code;
}

// The new vertex where edge a-b crosses a plane (distances da, db of opposite signs), as Mesa's clipper computes it
// (draw_pipe_clip.c): from the end nearer the plane (the inside end on a tie), r = a + t (b - a), t = da / (da - db).
// Two triangles sharing a clipped edge get bit-identical new vertices whichever way they walk it.
inline void intersect(const float* a, const float* b, float da, float db, int stride, float* r) {
  const bool from_a = std::abs(da) < std::abs(db) || (std::abs(da) == std::abs(db) && da >= 0);
  if (!from_a) std::swap(a, b), std::swap(da, db);
  const float t = da / (da - db);
  for (int k = 0; k < stride; ++k) r[k] = a[k] + t * (b[k] - a[k]);
}

// Sutherland-Hodgman against the planes in `planes` (bit mask), in Mesa's order and walk (so that the polygon and
// its fan are Mesa's): clips the polygon in a (count vertices; new[i] marks vertices made by clipping), using b and
// new_b as the second buffers. Returns the vertex count of the result, which ends in a and new_a.
int clip_polygon(float (*a)[kMaxStride], bool* new_a, float (*b)[kMaxStride], bool* new_b, int count, int stride,
                 unsigned planes) {
  for (int p = 0; p < 6 && count >= 3; ++p) {
    if (!(planes & (1u << p))) continue;
    int n = 0;
    for (int i = 0; i < count; ++i) {
      const float* cur = a[i];
      const float* next = a[(i + 1) % count];
      const float dc = plane_distance(cur, p), dn = plane_distance(next, p);
      if (dc >= 0) {
        std::copy(cur, cur + stride, b[n]);
        new_b[n++] = new_a[i];
      }
      if ((dc >= 0) != (dn >= 0)) {
        intersect(cur, next, dc, dn, stride, b[n]);
        new_b[n++] = true;
      }
    }
    for (int i = 0; i < n; ++i) {
      std::copy(b[i], b[i] + stride, a[i]);
      new_a[i] = new_b[i];
    }
    count = n;
  }
  return count;
}

// Round to nearest, ties to even (as the FPU's default mode); __builtin_rintf inlines where std::lrint is a call.
inline int32_t round_to_int(float v) { return int32_t(__builtin_rintf(v)); }

inline int floor_div256(int64_t v) { return int(v >= 0 ? v / 256 : -((-v + 255) / 256)); }

// A vertex's window position as Gallium has it: y down for a window-system framebuffer (viewport scale -h/2,
// translate H - (y + h/2)). The vertex stage's viewport transform (draw_llvm.c) fuses ndc * scale + translate into
// one multiply-add; the clipper's (draw_pipe_clip.c, plain C) rounds twice for the vertices it makes.
GalliumVertex gallium_window(const SetupParams& params, const float* clip, float inv_w, bool made_by_clipping) {
  const float half_w = float(params.vw) * 0.5f, half_h = float(params.vh) * 0.5f;
  const float translate_x = float(params.vx) + half_w;
  const float translate_y = float(params.fb_height) - (float(params.vy) + half_h);
  const float x = clip[0] * inv_w, y = clip[1] * inv_w;
  const float z = clip[2] * inv_w * 0.5f + 0.5f;  // exact either way
  if (made_by_clipping) return {x * half_w + translate_x, y * -half_h + translate_y, z};
  return {__builtin_fmaf(x, half_w, translate_x), __builtin_fmaf(y, -half_h, translate_y), z};
}

// The window positions of a vertex (clip position `clip`); `made_by_clipping` selects the clipper's viewport
// arithmetic (two roundings) over the vertex stage's (a fused multiply-add), as llvmpipe.
PreparedVertex prepare_vertex(const SetupParams& params, const float* clip, bool made_by_clipping) {
  PreparedVertex p{};
  p.outcode = uint8_t(finite_position(clip) ? outcode(clip) : kNotFinite);
  p.valid = clip[3] > 0;  // only a degenerate polygon on w = 0 survives clipping with w <= 0
  if (!p.valid || (p.outcode & kNotFinite)) return p;
  p.inv_w = 1.0f / clip[3];
  p.g = gallium_window(params, clip, p.inv_w, made_by_clipping);
  // Snap to 1/256 pixel. A vertex far outside the viewport is replaced by the clipper before anyone reads its snapped
  // position; the clamp only keeps its conversion to int defined.
  const auto snap = [](float v) { return round_to_int(std::clamp(v * 256.0f, -0x1p30f, 0x1p30f)); };
  p.X = snap(p.g.x);
  p.Y = params.fb_height * 256 - snap(p.g.y);  // mirrored: exactly the GL y-up value
  return p;
}

}  // namespace

void prepare_vertices(RasterScratch& scratch, SetupParams& params, uint32_t count) {
  std::vector<PreparedVertex>& prepared = scratch.inputs[size_t(scratch.input)].prepared;
  prepared.resize(count);
  PreparedVertex* out = prepared.data();
  const int stride = 4 + params.varying_count;
  pipeline_for(scratch, PipelineSide::caller, 0, count, 4096, [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) out[i] = prepare_vertex(params, params.vertices + i * stride, false);
  });
  params.prepared = out;
}

namespace {

// A triangle's plane setup as llvmpipe's (Mesa 22.3, lp_state_setup.c: float32, in Gallium's window frame with y
// down). llvmpipe hands the vertices over in their order when they wind counterclockwise on the GL screen, else with
// the first two swapped (lp_setup_tri.c, triangle_both); `order` is that order.
struct LpPlaneSetup {
  int order[3];
  float x0, y0;                      // the first vertex
  float dx01o, dy01o, dx20o, dy20o;  // edge vectors over the doubled area

  // The vertices are read in place through g (a copy of them on the stack, stored in 8- and 4-byte pieces, stalled
  // the loads below on store forwarding).
  LpPlaneSetup(const GalliumVertex* const* g, bool gl_ccw) : order{gl_ccw ? 0 : 1, gl_ccw ? 1 : 0, 2} {
    const GalliumVertex &v0 = *g[order[0]], &v1 = *g[order[1]], &v2 = *g[order[2]];
    const float dx01 = v0.x - v1.x, dy01 = v0.y - v1.y, dx20 = v2.x - v0.x, dy20 = v2.y - v0.y;
    const float ooa = 1.0f / (dx01 * dy20 - dy01 * dx20);
    x0 = v0.x, y0 = v0.y;
    dx01o = dx01 * ooa, dy01o = dy01 * ooa, dx20o = dx20 * ooa, dy20o = dy20 * ooa;
  }
  // The gradient of an attribute with values f[order[k]] at the vertices, per pixel in x and in y (down); false
  // when it is not finite (the triangle is collinear in float although not after snapping: a sliver).
  bool gradient(const float* f, float& dfdx, float& dfdy) const {
    const float d01 = f[order[0]] - f[order[1]], d20 = f[order[2]] - f[order[0]];
    dfdx = d01 * dy20o - d20 * dy01o;
    dfdy = d20 * dx01o - d01 * dx20o;
    return std::isfinite(dfdx) && std::isfinite(dfdy);
  }
  // gradient() of four attributes at once (f[k]: their values at vertex k), each lane's gradient zero where it is
  // not finite: the same IEEE operations per lane (SSE2, part of the baseline), a quarter of the instructions.
  void gradient4(const __m128* f, __m128& dfdx, __m128& dfdy) const {
    const __m128 d01 = _mm_sub_ps(f[order[0]], f[order[1]]), d20 = _mm_sub_ps(f[order[2]], f[order[0]]);
    dfdx = _mm_sub_ps(_mm_mul_ps(d01, _mm_set1_ps(dy20o)), _mm_mul_ps(d20, _mm_set1_ps(dy01o)));
    dfdy = _mm_sub_ps(_mm_mul_ps(d20, _mm_set1_ps(dx01o)), _mm_mul_ps(d01, _mm_set1_ps(dx20o)));
    const __m128 abs_mask = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff));
    const __m128 inf = _mm_set1_ps(std::numeric_limits<float>::infinity());
    const __m128 finite =
        _mm_and_ps(_mm_cmplt_ps(_mm_and_ps(dfdx, abs_mask), inf), _mm_cmplt_ps(_mm_and_ps(dfdy, abs_mask), inf));
    dfdx = _mm_and_ps(dfdx, finite);
    dfdy = _mm_and_ps(dfdy, finite);
  }
};

// The depth plane (lp_state_setup.c), relative to the first vertex moved by half a pixel: za is the depth at the
// center of image pixel (0, 0), zdx and zdy the steps per pixel (fragment_depth).
void depth_plane(const LpPlaneSetup& ps, const GalliumVertex* const* g, TriangleRecord& r) {
  const float z[3] = {g[0]->z, g[1]->z, g[2]->z};
  const float z0 = z[ps.order[0]];
  float dzdx, dzdy;
  if (!ps.gradient(z, dzdx, dzdy)) dzdx = dzdy = 0;  // a sliver: the first vertex's depth
  r.za = z0 - (dzdx * (ps.x0 - 0.5f) + dzdy * (ps.y0 - 0.5f));
  r.zdx = dzdx;
  r.zdy = dzdy;
}

// Copies n varyings four at a time and the rest one by one: a few floats per constant triangle, where std::copy
// became a call to memmove (2% of the caller's samples).
void copy_varyings(const float* from, int n, float* to) {
  int k = 0;
  for (; k + 4 <= n; k += 4) _mm_storeu_ps(to + k, _mm_loadu_ps(from + k));
  switch (n - k) {
    case 3:
      to[k + 2] = from[k + 2];
      [[fallthrough]];
    case 2:
      to[k + 1] = from[k + 1];
      [[fallthrough]];
    case 1:
      to[k] = from[k];
      break;
    default:
      break;
  }
}

// Sets up one triangle of vertices v (clip position and varyings) with their window positions pv, and bins it.
void emit_prepared(const SetupParams& params, const Scissor& sc, const float* const* v, const PreparedVertex* const* pv,
                   const float* flat_values, SetupChunk& chunk) {
  if (!(pv[0]->valid && pv[1]->valid && pv[2]->valid)) return;
  const float inv_w[3] = {pv[0]->inv_w, pv[1]->inv_w, pv[2]->inv_w};
  const GalliumVertex* g[3] = {&pv[0]->g, &pv[1]->g, &pv[2]->g};
  const int32_t X[3] = {pv[0]->X, pv[1]->X, pv[2]->X}, Y[3] = {pv[0]->Y, pv[1]->Y, pv[2]->Y};
  const int64_t area = int64_t(X[1] - X[0]) * (Y[2] - Y[0]) - int64_t(X[2] - X[0]) * (Y[1] - Y[0]);
  if (area == 0) return;
  if ((params.cull == 1 && area < 0) || (params.cull == 2 && area > 0)) return;
  // Counterclockwise in GL window coordinates, so the interior is on the left of every edge.
  const int order[3] = {0, area > 0 ? 1 : 2, area > 0 ? 2 : 1};
  const int32_t xmin = std::min({X[0], X[1], X[2]}), xmax = std::max({X[0], X[1], X[2]});
  const int32_t ymin = std::min({Y[0], Y[1], Y[2]}), ymax = std::max({Y[0], Y[1], Y[2]});
  // Pixels whose centers 256 i + 128 lie in [min, max].
  const int32_t x0 = std::max(sc.x0, floor_div256(xmin - 128 + 255)),
                x1 = std::min(sc.x1, floor_div256(xmax - 128) + 1);
  const int32_t y0 = std::max(sc.y0, floor_div256(ymin - 128 + 255)),
                y1 = std::min(sc.y1, floor_div256(ymax - 128) + 1);
  if (x0 >= x1 || y0 >= y1) return;
  // The record is written in place: a copy from the stack would reload it before its narrow stores are done.
  const uint32_t index = uint32_t(chunk.records.size());
  TriangleRecord& r = chunk.records.emplace_back(TriangleRecord::Uninitialized{});
  r.x0 = x0, r.x1 = x1, r.y0 = y0, r.y1 = y1;
  for (int k = 0; k < 3; ++k) {
    const int p = order[k], q = order[(k + 1) % 3];
    Edge& e = r.edges[k];
    e.a = Y[p] - Y[q];  // dE/dx
    e.b = X[q] - X[p];  // dE/dy
    // Tie rule (gl-raster-conventions.md item 6): an edge owns the centers on it when the interior lies on its +x
    // side, or above it for a horizontal edge.
    const bool inclusive = e.a > 0 || (e.a == 0 && e.b > 0);
    e.c = int64_t(e.a) * (128 - X[p]) + int64_t(e.b) * (128 - Y[p]) - (inclusive ? 0 : 1);
  }

  // Depth and varying planes from the unsnapped float window positions, in llvmpipe's arithmetic.
  r.front = area > 0;
  const LpPlaneSetup ps(g, area > 0);
  depth_plane(ps, g, r);
  r.rx = ps.x0;
  r.ry = float(params.fb_height) - ps.y0;  // GL y up
  const int n = params.varying_count;
  const float *v0 = v[0], *v1 = v[1], *v2 = v[2];
  r.varyings = uint32_t(chunk.varyings_used);
  // Equal varyings at the three vertices interpolate to themselves: no planes needed (uniformly colored meshes).
  r.constant =
      params.flat || n == 0 || (std::equal(v0 + 4, v0 + 4 + n, v1 + 4) && std::equal(v0 + 4, v0 + 4 + n, v2 + 4));
  if (r.constant) {
    const float* values = params.flat ? flat_values : v0 + 4;
    copy_varyings(values, n, chunk.append_varyings(size_t(n)));
  } else {
    float* c = chunk.append_varyings(3 * size_t(n + 1));
    float* cx = c + (n + 1);
    float* cy = c + 2 * (n + 1);
    // Planes of 1/w and of each varying times 1/w (perspective-correct), the y slope turned to GL's y up: four at
    // a time (Gouraud's 1/w, r, g, b in one), the rest one by one.
    int k = 0;
    for (; k + 4 <= n + 1; k += 4) {
      __m128 f[3];
      for (int i = 0; i < 3; ++i) {
        const __m128 values = _mm_loadu_ps(v[i] + 3 + k);  // lane 0 of the first group is w: 1/w's plane is of 1
        f[i] = _mm_mul_ps(k == 0 ? _mm_move_ss(values, _mm_set_ss(1.0f)) : values, _mm_set1_ps(inv_w[i]));
      }
      __m128 dfdx, dfdy;
      ps.gradient4(f, dfdx, dfdy);
      _mm_storeu_ps(c + k, f[ps.order[0]]);
      _mm_storeu_ps(cx + k, dfdx);
      _mm_storeu_ps(cy + k, _mm_xor_ps(dfdy, _mm_set1_ps(-0.0f)));
    }
    for (; k <= n; ++k) {
      float f[3];
      for (int i = 0; i < 3; ++i) f[i] = k == 0 ? inv_w[i] : v[i][3 + k] * inv_w[i];
      float dfdx, dfdy;
      if (!ps.gradient(f, dfdx, dfdy)) dfdx = dfdy = 0;
      c[k] = f[ps.order[0]];
      cx[k] = dfdx;
      cy[k] = -dfdy;
    }
  }
  ++chunk.rasterized;
  for (int ty = r.y0 / kTileSize; ty <= (r.y1 - 1) / kTileSize; ++ty)
    for (int tx = r.x0 / kTileSize; tx <= (r.x1 - 1) / kTileSize; ++tx)
      chunk.bins[size_t(ty) * params.tiles_x + tx].push_back(index);
}

// Sets up a triangle made by clipping (made_by_clipping[k]: vertex k is new) and bins it.
void emit_triangle(const SetupParams& params, const Scissor& sc, const float* v0, const float* v1, const float* v2,
                   const bool* made_by_clipping, const float* flat_values, SetupChunk& chunk) {
  const float* v[3] = {v0, v1, v2};
  PreparedVertex prepared[3];
  const PreparedVertex* p[3];
  for (int k = 0; k < 3; ++k) prepared[k] = prepare_vertex(params, v[k], made_by_clipping[k]), p[k] = &prepared[k];
  emit_prepared(params, sc, v, p, flat_values, chunk);
}

void setup_chunk_baseline(const SetupParams& params, std::span<const uint32_t> indices, size_t first, size_t count,
                          SetupChunk& chunk) {
  const int n = params.varying_count;
  const int stride = 4 + n;
  const Scissor sc = scissor(params);
  float a[kMaxClipVertices][kMaxStride], b[kMaxClipVertices][kMaxStride];
  bool new_a[kMaxClipVertices], new_b[kMaxClipVertices];
  float flat[kMaxVaryings];
  for (size_t t = first; t < first + count; ++t) {
    const float* v[3];
    for (int k = 0; k < 3; ++k) v[k] = params.vertices + size_t(indices[3 * t + k]) * stride;
    const PreparedVertex* p[3];
    for (int k = 0; k < 3; ++k) p[k] = params.prepared + indices[3 * t + k];
    if ((p[0]->outcode | p[1]->outcode | p[2]->outcode) & kNotFinite) continue;  // NaN or inf
    const unsigned c0 = p[0]->outcode, c1 = p[1]->outcode, c2 = p[2]->outcode;
    if (c0 & c1 & c2) continue;         // entirely outside one plane
    const float* provoking = v[2] + 4;  // flat shading: the last vertex, before clipping moves it
    if (!(c0 | c1 | c2)) {
      emit_prepared(params, sc, v, p, provoking, chunk);
      continue;
    }
    std::copy(provoking, provoking + n, flat);
    for (int k = 0; k < 3; ++k) std::copy(v[k], v[k] + stride, a[k]), new_a[k] = false;
    const int m = clip_polygon(a, new_a, b, new_b, 3, stride, c0 | c1 | c2);
    // Mesa's fan (emit_poly, last vertex provoking): (i - 1, i, 0).
    for (int i = 2; i < m; ++i) {
      const bool made[3] = {new_a[i - 1], new_a[i], new_a[0]};
      emit_triangle(params, sc, a[i - 1], a[i], a[0], made, flat, chunk);
    }
  }
}

// setup_chunk_baseline compiled for AVX2 with everything it calls inlined (VEX encodings, BMI, SSE4.1 rounding):
// the same IEEE operations (no contraction: -ffp-contract=off), so the same records.
[[gnu::target("avx2,fma,bmi,bmi2,lzcnt,popcnt"), gnu::flatten]] void setup_chunk_avx2(const SetupParams& params,
                                                                                      std::span<const uint32_t> indices,
                                                                                      size_t first, size_t count,
                                                                                      SetupChunk& chunk) {
  setup_chunk_baseline(params, indices, first, count, chunk);
}

// Sets up and bins the triangles [first, first + count) of the index list into chunk.
void setup_chunk(const SetupParams& params, std::span<const uint32_t> indices, size_t first, size_t count,
                 SetupChunk& chunk) {
  if (span_isa() >= 1)
    setup_chunk_avx2(params, indices, first, count, chunk);
  else
    setup_chunk_baseline(params, indices, first, count, chunk);
}

}  // namespace

WindowVertex to_window(const SetupParams& params, const float* clip) {
  const float inv_w = 1.0f / clip[3];
  const float half_w = float(params.vw) * 0.5f, half_h = float(params.vh) * 0.5f;
  return {clip[0] * inv_w * half_w + (float(params.vx) + half_w),
          clip[1] * inv_w * half_h + (float(params.vy) + half_h), clip[2] * inv_w * 0.5f + 0.5f, inv_w};
}

Scissor scissor(const SetupParams& params) {
  return {std::max(0, params.vx), std::max(0, params.vy), std::min(params.fb_width, params.vx + params.vw),
          std::min(params.fb_height, params.vy + params.vh)};
}

SetupParams setup_params(const Framebuffer& fb, const RasterState& state, const float* vertices, int varying_count) {
  SetupParams p;
  p.vertices = vertices;
  p.varying_count = varying_count;
  p.flat = state.flat;
  p.painter = state.painter;
  p.cull = state.cull == CullMode::back ? 1 : state.cull == CullMode::front ? 2 : 0;
  p.color_write = state.color_write && fb.has_color();  // a depth_only framebuffer: depth alone
  p.stencil_test = state.stencil_test;
  p.stencil[0] = state.stencil_back;
  p.stencil[1] = state.stencil_front;
  p.blend = state.blend;
  p.blend_function = state.blend_function;
  p.fb_width = fb.width();
  p.fb_height = fb.height();
  const bool whole = state.viewport.width <= 0 || state.viewport.height <= 0;
  p.vx = whole ? 0 : state.viewport.x;
  p.vy = whole ? 0 : state.viewport.y;
  p.vw = whole ? fb.width() : state.viewport.width;
  p.vh = whole ? fb.height() : state.viewport.height;
  p.tiles_x = (fb.width() + kTileSize - 1) / kTileSize;
  p.tiles_y = (fb.height() + kTileSize - 1) / kTileSize;
  return p;
}

bool stencil_passes(const StencilFace& face, uint8_t s) {
  const unsigned a = face.ref & face.mask, b = s & face.mask;
  switch (face.func) {
    case DepthFunc::never:
      return false;
    case DepthFunc::less:
      return a < b;
    case DepthFunc::equal:
      return a == b;
    case DepthFunc::lequal:
      return a <= b;
    case DepthFunc::greater:
      return a > b;
    case DepthFunc::notequal:
      return a != b;
    case DepthFunc::gequal:
      return a >= b;
    case DepthFunc::always:
      return true;
  }
  return true;
}

void stencil_apply(const StencilFace& face, StencilOp op, uint8_t& s) {
  unsigned v = s;
  switch (op) {
    case StencilOp::keep:
      return;
    case StencilOp::zero:
      v = 0;
      break;
    case StencilOp::replace:
      v = face.ref;
      break;
    case StencilOp::incr:
      v = s == 255 ? 255 : s + 1;
      break;
    case StencilOp::incr_wrap:
      v = uint8_t(s + 1);
      break;
    case StencilOp::decr:
      v = s == 0 ? 0 : s - 1;
      break;
    case StencilOp::decr_wrap:
      v = uint8_t(s - 1);
      break;
    case StencilOp::invert:
      v = uint8_t(~s);
      break;
  }
  s = uint8_t((s & ~face.write_mask) | (v & face.write_mask));
}

glm::u8vec4 blend_colors(const BlendFunction& f, const Vec4f& src, glm::u8vec4 dst) {
  // In 8-bit fixed point, as GPUs and llvmpipe blend an RGBA8 buffer: the source rounded to unorm8 like a stored
  // color, each product a b / 255 rounded by (x + (x >> 8) + 128) >> 8 (llvmpipe's lp_build_mul_norm), sums and
  // differences saturated to [0, 255]. Within 1 of the real-number formula (tested).
  const glm::u8vec4 s = to_color8(src);
  const auto factor = [&](BlendFactor b, int c) -> unsigned {
    switch (b) {
      case BlendFactor::zero:
        return 0;
      case BlendFactor::one:
        return 255;
      case BlendFactor::src_color:
        return s[c];
      case BlendFactor::one_minus_src_color:
        return 255u - s[c];
      case BlendFactor::dst_color:
        return dst[c];
      case BlendFactor::one_minus_dst_color:
        return 255u - dst[c];
      case BlendFactor::src_alpha:
        return s.w;
      case BlendFactor::one_minus_src_alpha:
        return 255u - s.w;
      case BlendFactor::dst_alpha:
        return dst.w;
      case BlendFactor::one_minus_dst_alpha:
        return 255u - dst.w;
    }
    return 0;
  };
  const auto mul = [](unsigned a, unsigned b) {
    const unsigned x = a * b;
    return int((x + (x >> 8) + 128) >> 8);
  };
  glm::u8vec4 out;
  for (int c = 0; c < 4; ++c) {
    const int sw = mul(s[c], factor(f.src, c)), dw = mul(dst[c], factor(f.dst, c));
    int v = 0;
    switch (f.equation) {
      case BlendEquation::add:
        v = sw + dw;
        break;
      case BlendEquation::subtract:
        v = sw - dw;
        break;
      case BlendEquation::reverse_subtract:
        v = dw - sw;
        break;
      case BlendEquation::min:
        v = std::min(s[c], dst[c]);
        break;
      case BlendEquation::max:
        v = std::max(s[c], dst[c]);
        break;
    }
    out[c] = uint8_t(std::clamp(v, 0, 255));
  }
  return out;
}

FragmentState fragment_state(const RasterState& state) {
  const bool depth_on = state.depth_test && !state.painter;
  return {depth_on ? state.depth_func : DepthFunc::always, depth_on && state.depth_write};
}

void reset_pass(SetupPass& pass, const SetupParams& params) {
  const size_t tiles = size_t(params.tiles_x) * params.tiles_y;
  pass.resize(kPassChunks);
  for (SetupChunk& chunk : pass) {
    chunk.records.clear();
    chunk.varyings_used = 0;
    chunk.rasterized = 0;
    chunk.bins.resize(tiles);
    for (auto& bin : chunk.bins) bin.clear();
  }
}

namespace {

// Sets up chunk c of a pass of triangle_count triangles starting at triangle first (see setup_chunks).
void setup_pass_chunk(SetupPass& pass, const SetupParams& params, std::span<const uint32_t> indices, size_t first,
                      size_t triangle_count, int64_t c) {
  const size_t start = first + size_t(c) * kChunkTriangles;
  setup_chunk(params, indices, start, std::min<size_t>(kChunkTriangles, first + triangle_count - start),
              pass[size_t(c)]);
}

// The triangles held by chunks [begin, end) of a pass.
uint64_t rasterized_in(const SetupPass& pass, int64_t begin, int64_t end) {
  uint64_t rasterized = 0;
  for (int64_t c = begin; c < end; ++c) rasterized += pass[size_t(c)].rasterized;
  return rasterized;
}

}  // namespace

uint64_t setup_chunks(RasterScratch& scratch, SetupPass& pass, const SetupParams& params,
                      std::span<const uint32_t> indices, size_t first, size_t triangle_count, int64_t chunk_begin,
                      int64_t chunk_end) {
  pipeline_for(scratch, PipelineSide::raster, chunk_begin, chunk_end, 1, [&](int64_t begin, int64_t end) {
    for (int64_t c = begin; c < end; ++c) setup_pass_chunk(pass, params, indices, first, triangle_count, c);
  });
  return rasterized_in(pass, chunk_begin, chunk_end);
}

uint64_t setup_chunks_while_raster_busy(RasterScratch& scratch, SetupPass& pass, const SetupParams& params,
                                        std::span<const uint32_t> indices, size_t first, size_t triangle_count,
                                        int64_t chunks, int64_t& taken) {
  // Chunks are claimed in order, so those set up here are [0, taken) and the job's [taken, chunks).
  std::atomic<int64_t> next{0};
  pipeline_for(scratch, PipelineSide::caller, 0, chunks, 1, [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) {
      if (raster_idle(scratch)) return;
      const int64_t c = next.fetch_add(1, std::memory_order_relaxed);
      if (c >= chunks) return;
      setup_pass_chunk(pass, params, indices, first, triangle_count, c);
    }
  });
  taken = std::min(next.load(), chunks);
  return rasterized_in(pass, 0, taken);
}

std::span<const uint32_t> painter_order(RasterScratch& scratch, const float* vertices, int stride,
                                        std::span<const uint32_t> indices) {
  const size_t triangles = indices.size() / 3;
  std::vector<std::pair<float, uint32_t>> keys(triangles);
  for (size_t t = 0; t < triangles; ++t) {
    float z = 0, w = 0;
    for (int k = 0; k < 3; ++k) {
      const float* v = vertices + size_t(indices[3 * t + k]) * stride;
      z += v[2];
      w += v[3];
    }
    // The normalized depth of the centroid; a centroid behind the eye sorts first (it is mostly clipped away).
    keys[t] = {w > 0 ? z / w : std::numeric_limits<float>::infinity(), uint32_t(t)};
  }
  std::stable_sort(keys.begin(), keys.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  scratch.order.resize(indices.size());
  for (size_t t = 0; t < triangles; ++t)
    for (int k = 0; k < 3; ++k) scratch.order[3 * t + k] = indices[3 * size_t(keys[t].second) + k];
  return scratch.order;
}

bool clip_segment(float* a, float* b, int varying_count) {
  if (!finite_position(a) || !finite_position(b)) return false;
  float t0 = 0, t1 = 1;
  for (int p = 0; p < 6; ++p) {
    const float da = plane_distance(a, p), db = plane_distance(b, p);
    if (da < 0 && db < 0) return false;
    if (da < 0) t0 = std::max(t0, da / (da - db));
    if (db < 0) t1 = std::min(t1, da / (da - db));
  }
  if (t0 > t1) return false;
  const int stride = 4 + varying_count;
  float na[kMaxStride], nb[kMaxStride];
  for (int k = 0; k < stride; ++k) {
    na[k] = a[k] + t0 * (b[k] - a[k]);
    nb[k] = a[k] + t1 * (b[k] - a[k]);
  }
  if (t0 > 0) std::copy(na, na + stride, a);
  if (t1 < 1) std::copy(nb, nb + stride, b);
  return true;
}

void check_draw(const Framebuffer& fb, const RasterState& state, std::span<const uint32_t> indices,
                uint32_t vertex_count, int arity, const char* what) {
  if (state.stencil_test && !fb.has_color())
    throw InvalidInput(
        fmt::format("{}s: the stencil test is on, but a depth-only framebuffer has no stencil buffer", what));
  if (indices.size() % size_t(arity) != 0)
    throw InvalidInput(fmt::format("{} indices: {} is not a multiple of {}", what, indices.size(), arity));
  const auto bad = std::find_if(indices.begin(), indices.end(), [&](uint32_t i) { return i >= vertex_count; });
  if (bad != indices.end())
    throw InvalidInput(fmt::format("{} index {} at position {} is out of range (vertex count {})", what, *bad,
                                   bad - indices.begin(), vertex_count));
}

}  // namespace tessera::raster3d::detail
