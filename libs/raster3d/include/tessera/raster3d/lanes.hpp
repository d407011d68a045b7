#pragma once
// The SIMD vocabulary of C++ fragment shaders on the quad stage (lane_shader.hpp), which reads like GLSL. A lane shader
// runs on eight fragments at once, two 2 x 2 quads, each value a `lanes::Float` (one float per lane) or a
// `lanes::vec2/vec3/vec4` of them, with GLSL's operators and built-ins (dot, normalize, reflect, mix, clamp, pow, ...),
// `dFdx`/`dFdy` by differences within each quad, as a GPU takes them, and `texture()`, whose MIPmap level of detail
// follows from those differences. Branches become masks: a comparison gives a `lanes::Mask`, `select(m, a, b)` picks
// per lane (GLSL's `m ? a : b`), `any(m)` skips work no lane needs, and a shader discards by clearing lanes of its
// `kept` mask. Where a lookup has no SIMD form (a cube map, a shadow map), `lane(k)` reads one lane and `set_lane`
// writes it.
//
// The operations are IEEE single precision in the same order as glm's (normalize is v * (1 / sqrt(dot(v, v)))), so a
// lane shader written like a per-pixel one computes the same values. Values are two 4-float vectors (GCC's vector
// extension: SSE on x86-64, NEON on ARM), one per quad, without intrinsics of any one instruction set.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <glm/glm.hpp>
#if defined(__SSE__)
#include <xmmintrin.h>
#elif defined(__ARM_NEON) && defined(__aarch64__)
#include <arm_neon.h>
#endif

#include "tessera/math/types.hpp"

namespace tessera {
class Texture2D;
}

namespace tessera::raster3d::lanes {

/// Lanes per call of a lane shader: two quads.
inline constexpr int kWidth = 8;

using Float4 = float __attribute__((vector_size(16)));  ///< one quad's floats
using Int4 = int32_t __attribute__((vector_size(16)));  ///< one quad's masks (0 or -1)

/// A float per lane.
struct Float {
  Float4 q[2];

  Float() = default;
  /// The same value on every lane (GLSL's scalars in vector expressions).
  Float(float s) : q{Float4{} + s, Float4{} + s} {}  // NOLINT(google-explicit-constructor): as GLSL's promotion
  Float(Float4 a, Float4 b) : q{a, b} {}
  /// Lanes [0, 8) from p.
  static Float load(const float* p) {
    Float f;
    std::memcpy(&f.q, p, sizeof f.q);
    return f;
  }
  /// Stores lanes [0, 8) to p.
  void store(float* p) const { std::memcpy(p, &q, sizeof q); }
  /// Lane k (0 to 7).
  float lane(int k) const { return q[k >> 2][k & 3]; }
  /// Sets lane k to v.
  void set_lane(int k, float v) { q[k >> 2][k & 3] = v; }
};

/// A condition per lane: all-ones where it holds, 0 elsewhere.
struct Mask {
  Int4 q[2];

  Mask() = default;
  /// The same on every lane.
  explicit Mask(bool b) : q{Int4{} - int32_t(b), Int4{} - int32_t(b)} {}
  Mask(Int4 a, Int4 b) : q{a, b} {}
  /// Whether the condition holds on lane k.
  bool lane(int k) const { return q[k >> 2][k & 3] != 0; }
};

// ---- Float arithmetic ----------------------------------------------------------------------------------------------

#define TESSERA_LANES_BINARY(OP)                                                                            \
  inline Float operator OP(const Float& a, const Float& b) { return {a.q[0] OP b.q[0], a.q[1] OP b.q[1]}; } \
  inline Float& operator OP##=(Float& a, const Float& b) { return a = a OP b; }
TESSERA_LANES_BINARY(+)
TESSERA_LANES_BINARY(-)
TESSERA_LANES_BINARY(*)
TESSERA_LANES_BINARY(/)
#undef TESSERA_LANES_BINARY
inline Float operator-(const Float& a) { return {-a.q[0], -a.q[1]}; }

#define TESSERA_LANES_COMPARE(OP) \
  inline Mask operator OP(const Float& a, const Float& b) { return {a.q[0] OP b.q[0], a.q[1] OP b.q[1]}; }
TESSERA_LANES_COMPARE(<)
TESSERA_LANES_COMPARE(<=)
TESSERA_LANES_COMPARE(>)
TESSERA_LANES_COMPARE(>=)
TESSERA_LANES_COMPARE(==)
TESSERA_LANES_COMPARE(!=)
#undef TESSERA_LANES_COMPARE

inline Mask operator&(const Mask& a, const Mask& b) { return {a.q[0] & b.q[0], a.q[1] & b.q[1]}; }
inline Mask operator|(const Mask& a, const Mask& b) { return {a.q[0] | b.q[0], a.q[1] | b.q[1]}; }
inline Mask operator!(const Mask& a) { return {~a.q[0], ~a.q[1]}; }
inline Mask& operator&=(Mask& a, const Mask& b) { return a = a & b; }
inline Mask& operator|=(Mask& a, const Mask& b) { return a = a | b; }
/// Whether the condition holds on some lane (GLSL's any) / on every lane (all).
inline bool any(const Mask& m) {
  const Int4 o = m.q[0] | m.q[1];
  return (o[0] | o[1] | o[2] | o[3]) != 0;
}
inline bool all(const Mask& m) {
  const Int4 a = m.q[0] & m.q[1];
  return (a[0] & a[1] & a[2] & a[3]) != 0;
}

/// Per lane, a where m holds, else b (GLSL's m ? a : b).
inline Float select(const Mask& m, const Float& a, const Float& b) {
  return {m.q[0] ? a.q[0] : b.q[0], m.q[1] ? a.q[1] : b.q[1]};
}
/// GLSL's min and max: b where b < a (resp. a < b), else a, as std::min and std::max.
inline Float min(const Float& a, const Float& b) { return select(b < a, b, a); }
inline Float max(const Float& a, const Float& b) { return select(a < b, b, a); }
/// GLSL's clamp: min(max(x, lo), hi).
inline Float clamp(const Float& x, const Float& lo, const Float& hi) { return min(max(x, lo), hi); }
/// GLSL's mix: a (1 - t) + b t, as glm::mix.
inline Float mix(const Float& a, const Float& b, const Float& t) { return a * (Float(1.0f) - t) + b * t; }
/// GLSL's abs.
inline Float abs(const Float& a) { return select(a < Float(0.0f), -a, a); }

/// f applied to every lane (the functions without a vector instruction on every target).
template <class F>
Float per_lane(const Float& a, F&& f) {
  Float r;
  for (int k = 0; k < 4; ++k) r.q[0][k] = f(a.q[0][k]), r.q[1][k] = f(a.q[1][k]);
  return r;
}
/// GLSL's sqrt, inversesqrt (1 / sqrt, as glm), floor, fract, exp2, log2, sin, cos and pow, lane by lane.
inline Float sqrt(const Float& a) {
#if defined(__SSE__)
  // The instruction (std::sqrt's result, correctly rounded, without its errno check per lane).
  return {Float4(_mm_sqrt_ps(__m128(a.q[0]))), Float4(_mm_sqrt_ps(__m128(a.q[1])))};
#elif defined(__ARM_NEON) && defined(__aarch64__)
  return {Float4(vsqrtq_f32(float32x4_t(a.q[0]))), Float4(vsqrtq_f32(float32x4_t(a.q[1])))};
#else
  return per_lane(a, [](float x) { return std::sqrt(x); });
#endif
}
inline Float inversesqrt(const Float& a) { return Float(1.0f) / sqrt(a); }
inline Float floor(const Float& a) {
  return per_lane(a, [](float x) { return std::floor(x); });
}
inline Float fract(const Float& a) { return a - floor(a); }
inline Float exp2(const Float& a) {
  return per_lane(a, [](float x) { return std::exp2(x); });
}
inline Float log2(const Float& a) {
  return per_lane(a, [](float x) { return std::log2(x); });
}
inline Float sin(const Float& a) {
  return per_lane(a, [](float x) { return std::sin(x); });
}
inline Float cos(const Float& a) {
  return per_lane(a, [](float x) { return std::cos(x); });
}
inline Float pow(const Float& a, const Float& b) {
  Float r;
  for (int k = 0; k < kWidth; ++k) r.set_lane(k, std::pow(a.lane(k), b.lane(k)));
  return r;
}
/// GLSL's step(edge, x): 0 where x < edge, else 1; smoothstep(e0, e1, x): t^2 (3 - 2t), t = clamp((x - e0) / (e1 -
/// e0), 0, 1).
inline Float step(const Float& edge, const Float& x) { return select(x < edge, Float(0.0f), Float(1.0f)); }
inline Float smoothstep(const Float& e0, const Float& e1, const Float& x) {
  const Float t = clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
  return t * t * (Float(3.0f) - Float(2.0f) * t);
}

/// GLSL's dFdx: per lane, the difference along x within its quad (lane 4q + 1 - 4q in row j, 4q + 3 - 4q + 2 in row
/// j + 1; FragmentBatch's layout), the same for both lanes of a row. dFdy: the difference along y (4q + 2 - 4q,
/// 4q + 3 - 4q + 1), the same for both lanes of a column.
inline Float dFdx(const Float& a) {  // NOLINT(readability-identifier-naming): GLSL's name
  const auto d = [](Float4 v) {
    return __builtin_shufflevector(v, v, 1, 1, 3, 3) - __builtin_shufflevector(v, v, 0, 0, 2, 2);
  };
  return {d(a.q[0]), d(a.q[1])};
}
inline Float dFdy(const Float& a) {  // NOLINT(readability-identifier-naming): GLSL's name
  const auto d = [](Float4 v) {
    return __builtin_shufflevector(v, v, 2, 3, 2, 3) - __builtin_shufflevector(v, v, 0, 1, 0, 1);
  };
  return {d(a.q[0]), d(a.q[1])};
}

// ---- Vectors of lanes
// ------------------------------------------------------------------------------------------------

/// N floats per lane: GLSL's vec2, vec3, vec4 on lanes (components x, y, z, w).
template <int N>
struct Vec;

template <>
struct Vec<2> {
  Float x, y;
  Vec() = default;
  Vec(Float x_, Float y_) : x(x_), y(y_) {}
  Vec(const Vec2f& v) : x(v.x), y(v.y) {}  // NOLINT(google-explicit-constructor): a uniform on every lane
  Float& operator[](int i) { return i == 0 ? x : y; }
  const Float& operator[](int i) const { return i == 0 ? x : y; }
  Vec2f lane(int k) const { return {x.lane(k), y.lane(k)}; }
};
template <>
struct Vec<3> {
  Float x, y, z;
  Vec() = default;
  Vec(Float x_, Float y_, Float z_) : x(x_), y(y_), z(z_) {}
  Vec(const Vec3f& v) : x(v.x), y(v.y), z(v.z) {}  // NOLINT(google-explicit-constructor)
  Float& operator[](int i) { return i == 0 ? x : i == 1 ? y : z; }
  const Float& operator[](int i) const { return i == 0 ? x : i == 1 ? y : z; }
  Vec3f lane(int k) const { return {x.lane(k), y.lane(k), z.lane(k)}; }
  void set_lane(int k, const Vec3f& v) { x.set_lane(k, v.x), y.set_lane(k, v.y), z.set_lane(k, v.z); }
};
template <>
struct Vec<4> {
  Float x, y, z, w;
  Vec() = default;
  Vec(Float x_, Float y_, Float z_, Float w_) : x(x_), y(y_), z(z_), w(w_) {}
  Vec(const Vec<3>& v, Float w_) : x(v.x), y(v.y), z(v.z), w(w_) {}
  Vec(const Vec4f& v) : x(v.x), y(v.y), z(v.z), w(v.w) {}  // NOLINT(google-explicit-constructor)
  Float& operator[](int i) { return i == 0 ? x : i == 1 ? y : i == 2 ? z : w; }
  const Float& operator[](int i) const { return i == 0 ? x : i == 1 ? y : i == 2 ? z : w; }
  Vec<3> xyz() const { return {x, y, z}; }
  Vec4f lane(int k) const { return {x.lane(k), y.lane(k), z.lane(k), w.lane(k)}; }
};
using vec2 = Vec<2>;
using vec3 = Vec<3>;
using vec4 = Vec<4>;

/// Component by component: a op b, a op s, s op a.
template <int N, class Op>
Vec<N> componentwise(const Vec<N>& a, const Vec<N>& b, Op op) {
  Vec<N> r;
  for (int i = 0; i < N; ++i) r[i] = op(a[i], b[i]);
  return r;
}
#define TESSERA_LANES_VEC_BINARY(OP)                                                   \
  template <int N>                                                                     \
  Vec<N> operator OP(const Vec<N>& a, const Vec<N>& b) {                               \
    return componentwise(a, b, [](const Float& u, const Float& v) { return u OP v; }); \
  }                                                                                    \
  template <int N>                                                                     \
  Vec<N> operator OP(const Vec<N>& a, const Float& s) {                                \
    Vec<N> r;                                                                          \
    for (int i = 0; i < N; ++i) r[i] = a[i] OP s;                                      \
    return r;                                                                          \
  }                                                                                    \
  template <int N>                                                                     \
  Vec<N> operator OP(const Float& s, const Vec<N>& a) {                                \
    Vec<N> r;                                                                          \
    for (int i = 0; i < N; ++i) r[i] = s OP a[i];                                      \
    return r;                                                                          \
  }                                                                                    \
  template <int N, class T>                                                            \
  Vec<N>& operator OP##=(Vec<N>& a, const T& b) {                                      \
    return a = a OP b;                                                                 \
  }
TESSERA_LANES_VEC_BINARY(+)
TESSERA_LANES_VEC_BINARY(-)
TESSERA_LANES_VEC_BINARY(*)
TESSERA_LANES_VEC_BINARY(/)
#undef TESSERA_LANES_VEC_BINARY
template <int N>
Vec<N> operator-(const Vec<N>& a) {
  Vec<N> r;
  for (int i = 0; i < N; ++i) r[i] = -a[i];
  return r;
}

/// GLSL's dot (summed left to right, as glm), cross, length, normalize (v * inversesqrt(dot(v, v)), as glm), reflect
/// (i - 2 dot(n, i) n), and the componentwise min, max, clamp, mix, select, dFdx, dFdy.
template <int N>
Float dot(const Vec<N>& a, const Vec<N>& b) {
  Float s = a[0] * b[0];
  for (int i = 1; i < N; ++i) s = s + a[i] * b[i];
  return s;
}
inline vec3 cross(const vec3& a, const vec3& b) {
  return {a.y * b.z - b.y * a.z, a.z * b.x - b.z * a.x, a.x * b.y - b.x * a.y};
}
template <int N>
Float length(const Vec<N>& a) {
  return sqrt(dot(a, a));
}
template <int N>
Vec<N> normalize(const Vec<N>& a) {
  return a * inversesqrt(dot(a, a));
}
template <int N>
Vec<N> reflect(const Vec<N>& i, const Vec<N>& n) {
  return i - Float(2.0f) * dot(n, i) * n;
}
template <int N>
Vec<N> min(const Vec<N>& a, const Vec<N>& b) {
  return componentwise(a, b, [](const Float& u, const Float& v) { return min(u, v); });
}
template <int N>
Vec<N> max(const Vec<N>& a, const Vec<N>& b) {
  return componentwise(a, b, [](const Float& u, const Float& v) { return max(u, v); });
}
template <int N>
Vec<N> clamp(const Vec<N>& x, const Float& lo, const Float& hi) {
  Vec<N> r;
  for (int i = 0; i < N; ++i) r[i] = clamp(x[i], lo, hi);
  return r;
}
template <int N>
Vec<N> mix(const Vec<N>& a, const Vec<N>& b, const Float& t) {
  Vec<N> r;
  for (int i = 0; i < N; ++i) r[i] = mix(a[i], b[i], t);
  return r;
}
template <int N>
Vec<N> select(const Mask& m, const Vec<N>& a, const Vec<N>& b) {
  Vec<N> r;
  for (int i = 0; i < N; ++i) r[i] = select(m, a[i], b[i]);
  return r;
}
template <int N>
Vec<N> dFdx(const Vec<N>& a) {  // NOLINT(readability-identifier-naming): GLSL's name
  Vec<N> r;
  for (int i = 0; i < N; ++i) r[i] = dFdx(a[i]);
  return r;
}
template <int N>
Vec<N> dFdy(const Vec<N>& a) {  // NOLINT(readability-identifier-naming): GLSL's name
  Vec<N> r;
  for (int i = 0; i < N; ++i) r[i] = dFdy(a[i]);
  return r;
}

/// GLSL's matrix times vector: the columns weighted by v's components, summed left to right (as glm).
inline vec3 operator*(const Mat3f& m, const vec3& v) {
  vec3 r;
  for (int i = 0; i < 3; ++i) r[i] = (Float(m[0][i]) * v.x + Float(m[1][i]) * v.y) + Float(m[2][i]) * v.z;
  return r;
}
inline vec4 operator*(const Mat4f& m, const vec4& v) {
  vec4 r;
  for (int i = 0; i < 4; ++i)
    r[i] = ((Float(m[0][i]) * v.x + Float(m[1][i]) * v.y) + Float(m[2][i]) * v.z) + Float(m[3][i]) * v.w;
  return r;
}

/// GLSL's texture(sampler2D, uv): the texture's filter at uv, the MIPmap level of detail of each quad from its
/// coordinates' differences (lanes 1 - 0 and 2 - 0, as Texture2D::lod), as a GPU and the GLSL executor take it.
/// Texture2D::sample_lanes does the lookups (gathers where the CPU has them).
vec4 texture(const Texture2D& t, const vec2& uv);

}  // namespace tessera::raster3d::lanes
