#pragma once
// The register program a shader compiles to (compile.cpp writes it, execute.cpp runs it).
//
// Every value is scalarized: a vec3 is three registers, a mat4 sixteen (column-major), a struct its members'. A
// register holds one 32-bit value per lane (float, int32, or a bool as 0 / all-ones), kLanes lanes: the executor runs
// each instruction over all lanes of a batch at once (a plain loop over lanes that the compiler vectorizes), so an
// instruction's dispatch costs once per batch, not per pixel.
//
// Control flow is flattened where it can be (if / else become masked writes: `dst = select(mask, value, dst)`) and
// kept as jumps where it must (loops, and skipping a branch no lane takes): the compiler manages the execution masks
// in ordinary bool registers, the executor only knows jump, jump_if_none and jump_if_any.
//
// Registers that depend only on constants and uniforms are computed once per scratch (the prologue), not per batch.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "tessera/raster3d/quad_stage.hpp"

namespace tessera::glsl::ir {

inline constexpr int kLanes = raster3d::FragmentBatch::kLanes;

enum class Op : uint8_t {
  // dst = f(a), floats
  mov,  // any 32-bit value
  fneg,
  fabs,
  fsign,
  ffloor,
  fceil,
  ffract,  // a - floor(a)
  ftrunc,
  fround,  // roundEven
  fsqrt,
  frsqrt,  // 1 / sqrt(a)
  fexp,
  fexp2,
  flog,
  flog2,
  fsin,
  fcos,
  ftan,
  fasin,
  facos,
  fatan,
  fsinh,
  fcosh,
  ftanh,
  // dst = f(a, b), floats
  fadd,
  fsub,
  fmul,
  fdiv,
  fmin,  // GLSL min: b < a ? b : a
  fmax,  // GLSL max: a < b ? b : a
  fpow,
  fatan2,  // atan(y = a, x = b)
  fmod,    // a - b * floor(a / b)
  fstep,   // b < a ? 0 : 1 (edge a, x b)
  // dst = f(a, b, c), floats
  fclamp,       // min(max(a, b), c)
  fmix,         // a * (1 - c) + b * c
  fsmoothstep,  // edges a, b; x c: t = clamp((c - a) / (b - a), 0, 1), t * t * (3 - 2 t)
  // float comparisons: dst (bool) = a OP b
  flt,
  fle,
  fgt,
  fge,
  feq,
  fne,
  // ints (int32, wrapping)
  iadd,
  isub,
  imul,
  idiv,  // 0 when b is 0 (GLSL leaves it undefined)
  imod,  // 0 when b is 0
  ineg,
  iabs,
  imin,
  imax,
  ilt,
  ile,
  igt,
  ige,
  ieq,
  ine,
  ishl,
  ishr,  // arithmetic
  // conversions
  itof,  // int -> float
  ftoi,  // float -> int, truncating (an out-of-range or NaN value gives 0)
  btof,  // bool -> 0.0 or 1.0
  btoi,  // bool -> 0 or 1
  // bitwise on 32-bit values: the bool operators (bools are 0 / all-ones) and ints' &, |, ^, ~
  band,
  bor,
  bxor,
  bnot,
  select,  // dst = a (bool) ? b : c
  // quad derivatives of a (float), fragment stage only: see FragmentBatch for the lane layout
  dfdx,
  dfdy,
  // texture sampling: dst .. dst + 3 = RGBA of sampler `unit` (the program's sampler index, resolved to a texture
  // unit at draw time) at (a, b) for 2D, direction (a, b, c) for a cube map. The level of detail is implicit
  // (from the quad derivatives of the coordinates), plus the bias in d (_bias), or explicit in d (_lod).
  tex2d,
  tex2d_bias,
  tex2d_lod,
  texcube,
  texcube_bias,
  texcube_lod,
  // dynamic indexing into a run of registers: dst = register (a + clamp(int b, 0, unit - 1) * c) of each lane,
  // a, c and unit being numbers (first register, stride, element count), b an int register
  gather,
  // control flow: `target` is an instruction index in the same code
  jump,          // always
  jump_if_none,  // when no lane in use has a (bool) set
  jump_if_any,   // when some lane in use has a set; counts toward the iteration limit (loops jump back with it)
};

/// One instruction. Operands a to d are registers (or numbers, as the op says); unused ones are 0.
struct Instr {
  Op op = Op::mov;
  uint16_t unit = 0;  // sampler index (tex*), element count (gather)
  uint32_t dst = 0;
  uint32_t a = 0, b = 0, c = 0, d = 0;
  int32_t target = 0;  // jump target
};

/// A compiled stage.
struct Stage {
  uint32_t register_count = 0;
  /// Registers holding a constant (the 32-bit pattern) in every lane.
  std::vector<std::pair<uint32_t, uint32_t>> constants;
  /// Registers holding a uniform word (index into the program's uniform storage, 32-bit words) in every lane.
  std::vector<std::pair<uint32_t, uint32_t>> uniforms;
  /// Runs once after constants and uniforms are in place (reads and writes registers like `code`, all lanes alike).
  std::vector<Instr> prologue;
  /// Runs once per batch.
  std::vector<Instr> code;
  /// Inputs: register <- input slot. Vertex stage: slot = attribute component (see Program's attribute table);
  /// fragment stage: slot = varying float index, or one of the kFrag* slots below.
  std::vector<std::pair<uint32_t, uint32_t>> inputs;
  /// Outputs: register -> output slot. Vertex stage: slots 0-3 gl_Position, 4 + k varying float k; fragment stage:
  /// slots 0-3 the color (RGBA).
  std::vector<std::pair<uint32_t, uint32_t>> outputs;
  /// Fragment stage: the bool register that starts all-ones and that discard clears (kept lanes); unused (0) in a
  /// program that never discards... and in the vertex stage.
  uint32_t kept = 0;
  bool discards = false;
};

/// Fragment input slots past the varyings.
inline constexpr uint32_t kFragCoord = 1000;    // + 0..3: gl_FragCoord x, y, z, w
inline constexpr uint32_t kFrontFacing = 1004;  // gl_FrontFacing (bool)

/// A loop guard: the executor throws once a batch's loops have run more instructions than this (each backward jump
/// counts the instructions of the body it repeats): a fraction of a second of work, where an endless loop would hang.
inline constexpr int64_t kMaxLoopWork = int64_t(1) << 20;

/// The largest program the compiler makes: registers per stage (a register file is 256 bytes a register per thread)
/// and instructions per stage. A source past them (a huge array indexed by a variable, say) is a compile error.
inline constexpr uint32_t kMaxRegisters = uint32_t(1) << 16;
inline constexpr size_t kMaxInstructions = size_t(1) << 20;

}  // namespace tessera::glsl::ir
