// The executor's loop over instructions, compiled once per instruction set: execute.cpp includes it for the baseline
// (x86-64), execute_avx2.cpp with -mavx2 -mfma, each in its own namespace (TESSERA_GLSL_ISA). Every instruction is a
// plain loop over the lanes that GCC vectorizes; -ffp-contract=off (CMakeLists.txt) keeps a * b + c two roundings in
// both, so the sets give the same pixels. Transcendentals and texture reads are per lane.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "execute.hpp"
#include "glsl_math.hpp"
#include "tessera/core/error.hpp"

namespace tessera::glsl::TESSERA_GLSL_ISA {
namespace {

using I32 = int32_t __attribute__((may_alias));
using U32 = uint32_t __attribute__((may_alias));
using ir::kLanes;
using ir::Op;

/// GLSL's min and max (the second operand wins a NaN comparison, as SPIR-V's FMin/FMax leave open).
inline float glsl_min(float a, float b) { return b < a ? b : a; }
inline float glsl_max(float a, float b) { return a < b ? b : a; }

/// float -> int truncating; NaN and values outside int32 give 0 (GLSL leaves them undefined; no UB here).
inline int32_t to_int(float x) { return std::fabs(x) < 2147483648.0f ? int32_t(x) : 0; }

/// The level of detail of a quad's 2D coordinates (lanes 4q..4q+3): its lane-0 differences to the right and up.
inline float quad_lod(const Texture2D& t, const float* u, const float* v, int lane0) {
  const glm::vec2 ddx(u[lane0 + 1] - u[lane0], v[lane0 + 1] - v[lane0]);
  const glm::vec2 ddy(u[lane0 + 2] - u[lane0], v[lane0 + 2] - v[lane0]);
  return t.lod(ddx, ddy);
}

/// The level of detail of a quad's cube directions: the face coordinates' differences on lane 0's face (0 when the
/// quad spans faces).
inline float quad_cube_lod(const CubeMap& cube, const float* x, const float* y, const float* z, int lane0) {
  CubeCoord c[3];
  for (int k = 0; k < 3; ++k) c[k] = cube_coord(glm::vec3(x[lane0 + k], y[lane0 + k], z[lane0 + k]));
  if (c[1].face != c[0].face || c[2].face != c[0].face) return 0.0f;
  return cube.face(c[0].face).lod(c[1].st - c[0].st, c[2].st - c[0].st);
}

void sample(const ir::Instr& in, float* file, int n, bool fragment, const BoundSampler* samplers) {
  float* out[4];
  for (int k = 0; k < 4; ++k) out[k] = file + size_t(in.dst + uint32_t(k)) * kLanes;
  const float* a = file + size_t(in.a) * kLanes;
  const float* b = file + size_t(in.b) * kLanes;
  const float* c = file + size_t(in.c) * kLanes;
  const float* d = file + size_t(in.d) * kLanes;
  const BoundSampler& s = samplers[in.unit];
  const bool cube = in.op == Op::texcube || in.op == Op::texcube_bias || in.op == Op::texcube_lod;
  const bool explicit_lod = in.op == Op::tex2d_lod || in.op == Op::texcube_lod;
  const bool bias = in.op == Op::tex2d_bias || in.op == Op::texcube_bias;
  if (cube ? !s.cube_map : !s.texture) {
    // An unbound unit reads as OpenGL's incomplete texture.
    for (int l = 0; l < n; ++l) out[0][l] = out[1][l] = out[2][l] = 0.0f, out[3][l] = 1.0f;
    return;
  }
  if (!cube) {
    // 2D textures: the lanes at once (Texture2D::sample_lanes; SIMD for 8-bit textures), each quad's level of detail
    // from its coordinates' differences.
    alignas(32) float lods[kLanes];
    for (int q = 0; q < n; q += 4) {
      const float lod = explicit_lod || !fragment ? 0.0f : quad_lod(*s.texture, a, b, q);
      for (int l = q; l < q + 4; ++l) lods[l] = explicit_lod ? d[l] : bias ? lod + d[l] : lod;
    }
    s.texture->sample_lanes(a, b, lods, out, n);
    return;
  }
  for (int q = 0; q < n; q += 4) {
    float lod = 0.0f;
    if (!explicit_lod && fragment) lod = cube ? quad_cube_lod(*s.cube_map, a, b, c, q) : quad_lod(*s.texture, a, b, q);
    for (int l = q; l < q + 4; ++l) {
      const float level = explicit_lod ? d[l] : bias ? lod + d[l] : lod;
      const glm::vec4 t = cube ? s.cube_map->lookup(glm::vec3(a[l], b[l], c[l]), level)
                               : s.texture->sample(glm::vec2(a[l], b[l]), level);
      out[0][l] = t.x, out[1][l] = t.y, out[2][l] = t.z, out[3][l] = t.w;
    }
  }
}

}  // namespace

void run_code(std::span<const ir::Instr> code, float* file, int lanes_in_use, bool fragment,
              const BoundSampler* samplers) {
  // Whole quads (the derivatives read all four lanes), rounded up to 8 lanes so the loops have no scalar tail.
  const int n = std::min(kLanes, (lanes_in_use + 7) & ~7);
  int64_t loop_work = 0;  // instructions repeated by backward jumps (ir::kMaxLoopWork)
  const auto reg = [file](uint32_t r) { return file + size_t(r) * kLanes; };
  for (size_t pc = 0; pc < code.size();) {
    const ir::Instr& in = code[pc++];
    float* d = reg(in.dst);
    const float* a = reg(in.a);
    const float* b = reg(in.b);
    const float* c = reg(in.c);
    U32* du = reinterpret_cast<U32*>(d);
    I32* di = reinterpret_cast<I32*>(d);
    const U32* au = reinterpret_cast<const U32*>(a);
    const U32* bu = reinterpret_cast<const U32*>(b);
    const U32* cu = reinterpret_cast<const U32*>(c);
    const I32* ai = reinterpret_cast<const I32*>(a);
    const I32* bi = reinterpret_cast<const I32*>(b);
// One case: `expr` for every lane in use, then break (no case falls through).
#define TESSERA_LANES(expr)           \
  for (int l = 0; l < n; ++l) (expr); \
  break
    switch (in.op) {
      case Op::mov:
        TESSERA_LANES(du[l] = au[l]);
      case Op::fneg:
        TESSERA_LANES(d[l] = -a[l]);
      case Op::fabs:
        TESSERA_LANES(d[l] = std::fabs(a[l]));
      case Op::fsign:
        TESSERA_LANES(d[l] = a[l] > 0.0f ? 1.0f : a[l] < 0.0f ? -1.0f : 0.0f);
      case Op::ffloor:
        TESSERA_LANES(d[l] = std::floor(a[l]));
      case Op::fceil:
        TESSERA_LANES(d[l] = std::ceil(a[l]));
      case Op::ffract:
        TESSERA_LANES(d[l] = a[l] - std::floor(a[l]));
      case Op::ftrunc:
        TESSERA_LANES(d[l] = std::trunc(a[l]));
      case Op::fround:
        TESSERA_LANES(d[l] = __builtin_rintf(a[l]));
      case Op::fsqrt:
        TESSERA_LANES(d[l] = std::sqrt(a[l]));
      case Op::frsqrt:
        TESSERA_LANES(d[l] = 1.0f / std::sqrt(a[l]));
      case Op::fexp:
        TESSERA_LANES(d[l] = std::exp(a[l]));
      case Op::fexp2:
        TESSERA_LANES(d[l] = std::exp2(a[l]));
      case Op::flog:
        TESSERA_LANES(d[l] = std::log(a[l]));
      case Op::flog2:
        TESSERA_LANES(d[l] = std::log2(a[l]));
      case Op::fsin:
        TESSERA_LANES(d[l] = std::sin(a[l]));
      case Op::fcos:
        TESSERA_LANES(d[l] = std::cos(a[l]));
      case Op::ftan:
        TESSERA_LANES(d[l] = std::tan(a[l]));
      case Op::fasin:
        TESSERA_LANES(d[l] = std::asin(a[l]));
      case Op::facos:
        TESSERA_LANES(d[l] = std::acos(a[l]));
      case Op::fatan:
        TESSERA_LANES(d[l] = std::atan(a[l]));
      case Op::fsinh:
        TESSERA_LANES(d[l] = std::sinh(a[l]));
      case Op::fcosh:
        TESSERA_LANES(d[l] = std::cosh(a[l]));
      case Op::ftanh:
        TESSERA_LANES(d[l] = std::tanh(a[l]));
      case Op::fadd:
        TESSERA_LANES(d[l] = a[l] + b[l]);
      case Op::fsub:
        TESSERA_LANES(d[l] = a[l] - b[l]);
      case Op::fmul:
        TESSERA_LANES(d[l] = a[l] * b[l]);
      case Op::fdiv:
        TESSERA_LANES(d[l] = a[l] / b[l]);
      case Op::fmin:
        TESSERA_LANES(d[l] = glsl_min(a[l], b[l]));
      case Op::fmax:
        TESSERA_LANES(d[l] = glsl_max(a[l], b[l]));
      case Op::fpow:
        for (int l = 0; l < n; ++l) d[l] = glsl_pow(a[l], b[l]);
        // The rare lanes the fast form does not cover (x <= 0 or subnormal, infinite or NaN operands) again, exactly.
        for (int l = 0; l < n; ++l)
          if (!glsl_pow_covers(a[l], b[l])) d[l] = std::pow(a[l], b[l]);
        break;
      case Op::fatan2:
        TESSERA_LANES(d[l] = std::atan2(a[l], b[l]));
      case Op::fmod:
        TESSERA_LANES(d[l] = a[l] - b[l] * std::floor(a[l] / b[l]));
      case Op::fstep:
        TESSERA_LANES(d[l] = b[l] < a[l] ? 0.0f : 1.0f);
      case Op::fclamp:
        TESSERA_LANES(d[l] = glsl_min(glsl_max(a[l], b[l]), c[l]));
      case Op::fmix:
        TESSERA_LANES(d[l] = a[l] * (1.0f - c[l]) + b[l] * c[l]);
      case Op::fsmoothstep:
        for (int l = 0; l < n; ++l) {
          const float t = glsl_min(glsl_max((c[l] - a[l]) / (b[l] - a[l]), 0.0f), 1.0f);
          d[l] = t * t * (3.0f - 2.0f * t);
        }
        break;
      case Op::flt:
        TESSERA_LANES(du[l] = a[l] < b[l] ? ~0u : 0u);
      case Op::fle:
        TESSERA_LANES(du[l] = a[l] <= b[l] ? ~0u : 0u);
      case Op::fgt:
        TESSERA_LANES(du[l] = a[l] > b[l] ? ~0u : 0u);
      case Op::fge:
        TESSERA_LANES(du[l] = a[l] >= b[l] ? ~0u : 0u);
      case Op::feq:
        TESSERA_LANES(du[l] = a[l] == b[l] ? ~0u : 0u);
      case Op::fne:
        TESSERA_LANES(du[l] = a[l] != b[l] ? ~0u : 0u);
      // Ints wrap: the arithmetic is on uint32_t.
      case Op::iadd:
        TESSERA_LANES(du[l] = au[l] + bu[l]);
      case Op::isub:
        TESSERA_LANES(du[l] = au[l] - bu[l]);
      case Op::imul:
        TESSERA_LANES(du[l] = au[l] * bu[l]);
      case Op::idiv:
        TESSERA_LANES(di[l] = bi[l] == 0 ? 0 : (bi[l] == -1 ? int32_t(0u - au[l]) : ai[l] / bi[l]));
      case Op::imod:
        TESSERA_LANES(di[l] = bi[l] == 0 || bi[l] == -1 ? 0 : ai[l] % bi[l]);
      case Op::ineg:
        TESSERA_LANES(du[l] = 0u - au[l]);
      case Op::iabs:
        TESSERA_LANES(du[l] = ai[l] < 0 ? 0u - au[l] : au[l]);
      case Op::imin:
        TESSERA_LANES(di[l] = std::min<int32_t>(ai[l], bi[l]));
      case Op::imax:
        TESSERA_LANES(di[l] = std::max<int32_t>(ai[l], bi[l]));
      case Op::ilt:
        TESSERA_LANES(du[l] = ai[l] < bi[l] ? ~0u : 0u);
      case Op::ile:
        TESSERA_LANES(du[l] = ai[l] <= bi[l] ? ~0u : 0u);
      case Op::igt:
        TESSERA_LANES(du[l] = ai[l] > bi[l] ? ~0u : 0u);
      case Op::ige:
        TESSERA_LANES(du[l] = ai[l] >= bi[l] ? ~0u : 0u);
      case Op::ieq:
        TESSERA_LANES(du[l] = au[l] == bu[l] ? ~0u : 0u);
      case Op::ine:
        TESSERA_LANES(du[l] = au[l] != bu[l] ? ~0u : 0u);
      case Op::ishl:
        TESSERA_LANES(du[l] = au[l] << (bu[l] & 31u));
      case Op::ishr:
        TESSERA_LANES(di[l] = ai[l] >> (bu[l] & 31u));
      case Op::itof:
        TESSERA_LANES(d[l] = float(ai[l]));
      case Op::ftoi:
        TESSERA_LANES(di[l] = to_int(a[l]));
      case Op::btof:
        TESSERA_LANES(d[l] = au[l] ? 1.0f : 0.0f);
      case Op::btoi:
        TESSERA_LANES(du[l] = au[l] ? 1u : 0u);
      case Op::band:
        TESSERA_LANES(du[l] = au[l] & bu[l]);
      case Op::bor:
        TESSERA_LANES(du[l] = au[l] | bu[l]);
      case Op::bxor:
        TESSERA_LANES(du[l] = au[l] ^ bu[l]);
      case Op::bnot:
        TESSERA_LANES(du[l] = ~au[l]);
      case Op::select:
        TESSERA_LANES(du[l] = au[l] ? bu[l] : cu[l]);
      case Op::dfdx:
        // Fine derivatives: each row of a quad its own difference (FragmentBatch's lane layout).
        for (int l = 0; l < n; ++l) {
          const int row0 = l & ~1;
          d[l] = fragment ? a[row0 + 1] - a[row0] : 0.0f;
        }
        break;
      case Op::dfdy:
        for (int l = 0; l < n; ++l) {
          const int column0 = (l & ~3) + (l & 1);
          d[l] = fragment ? a[column0 + 2] - a[column0] : 0.0f;
        }
        break;
      case Op::tex2d:
      case Op::tex2d_bias:
      case Op::tex2d_lod:
      case Op::texcube:
      case Op::texcube_bias:
      case Op::texcube_lod:
        sample(in, file, n, fragment, samplers);
        break;
      case Op::gather: {
        const float* first = reg(in.a);
        const int last = int(in.unit) - 1;
        for (int l = 0; l < n; ++l) {
          const int e = std::clamp(bi[l], 0, last);
          du[l] = reinterpret_cast<const U32*>(first + size_t(e) * in.c * kLanes)[l];
        }
        break;
      }
      case Op::jump:
        pc = size_t(in.target);
        break;
      case Op::jump_if_none:
      case Op::jump_if_any: {
        uint32_t any = 0;
        for (int l = 0; l < lanes_in_use; ++l) any |= au[l];
        if ((in.op == Op::jump_if_any) == (any != 0)) {
          if (in.op == Op::jump_if_any && (loop_work += int64_t(pc - size_t(in.target))) > ir::kMaxLoopWork)
            throw InvalidInput("a shader's loops ran more than " + std::to_string(ir::kMaxLoopWork) +
                               " instructions for one batch of pixels (an endless loop?)");
          pc = size_t(in.target);
        }
        break;
      }
    }
#undef TESSERA_LANES
  }
}

}  // namespace tessera::glsl::TESSERA_GLSL_ISA
