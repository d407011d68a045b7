#pragma once
// The executor: runs a compiled stage (ir.hpp) over the kLanes lanes of a batch, on the widest instruction set the
// CPU has (execute.cpp: baseline x86-64; execute_avx2.cpp: the same source built for AVX2, chosen at run time).
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "ir.hpp"
#include "tessera/image/texture.hpp"

namespace tessera::glsl {

/// The texture a sampler reads during a draw (null when its unit has none bound).
struct BoundSampler {
  const Texture2D* texture = nullptr;
  const CubeMap* cube_map = nullptr;
};

/// Runs `code` over the register file `file` (register r's lanes at file + r kLanes) for lanes [0, lanes_in_use),
/// once per instruction set (execute_impl.hpp); Registers::run picks the widest the CPU has.
namespace baseline {
void run_code(std::span<const ir::Instr> code, float* file, int lanes_in_use, bool fragment,
              const BoundSampler* samplers);
}
namespace avx2 {
void run_code(std::span<const ir::Instr> code, float* file, int lanes_in_use, bool fragment,
              const BoundSampler* samplers);
}
namespace avx512 {
void run_code(std::span<const ir::Instr> code, float* file, int lanes_in_use, bool fragment,
              const BoundSampler* samplers);
}

/// A cap on the executor's instruction set, for the tests that compare the sets: 0 the baseline, 1 AVX2, -1 (the
/// default) the widest the CPU has.
int& executor_isa_cap();

/// One thread's register file for a stage: constants and uniforms in place and the prologue run, ready for batches.
class Registers {
 public:
  /// `fragment`: the stage runs on quads (dfdx, dfdy and implicit level of detail are quad differences); otherwise
  /// implicit level of detail is 0 and derivatives are 0.
  Registers(const ir::Stage& stage, std::span<const uint32_t> uniform_words, std::span<const BoundSampler> samplers,
            bool fragment);

  /// Register r's kLanes lanes.
  float* lanes(uint32_t r) { return file_.get() + size_t(r) * ir::kLanes; }
  uint32_t* ulanes(uint32_t r) { return reinterpret_cast<uint32_t*>(lanes(r)); }

  /// Runs the stage's code over lanes [0, lanes_in_use) (the others compute garbage). Throws InvalidInput when a
  /// batch's loops run more than ir::kMaxLoopWork instructions.
  void run(int lanes_in_use);

 private:
  const ir::Stage& stage_;
  std::vector<BoundSampler> samplers_;
  bool fragment_;
  std::unique_ptr<float[]> file_;  // not zeroed: a register is written before it is read
};

}  // namespace tessera::glsl
