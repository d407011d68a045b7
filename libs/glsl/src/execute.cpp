// The baseline executor (x86-64) and the register file it runs on; the choice of an instruction set.
#define TESSERA_GLSL_ISA baseline
#include "execute_impl.hpp"
#include "tessera/core/cpu.hpp"

namespace tessera::glsl {

Registers::Registers(const ir::Stage& stage, std::span<const uint32_t> uniform_words,
                     std::span<const BoundSampler> samplers, bool fragment)
    : stage_(stage),
      samplers_(samplers.begin(), samplers.end()),
      fragment_(fragment),
      file_(std::make_unique_for_overwrite<float[]>(size_t(stage.register_count) * ir::kLanes)) {
  for (const auto& [r, bits] : stage.constants) std::fill_n(ulanes(r), ir::kLanes, bits);
  for (const auto& [r, word] : stage.uniforms) std::fill_n(ulanes(r), ir::kLanes, uniform_words[word]);
  baseline::run_code(stage.prologue, file_.get(), ir::kLanes, fragment_, samplers_.data());
}

int& executor_isa_cap() {
  static int cap = -1;
  return cap;
}

void Registers::run(int lanes_in_use) {
  if (stage_.discards) std::fill_n(ulanes(stage_.kept), ir::kLanes, ~0u);
  static const SimdLevel cpu = simd_level();
  const int cap = executor_isa_cap();
  if (cpu >= SimdLevel::avx512 && cap < 0)
    avx512::run_code(stage_.code, file_.get(), lanes_in_use, fragment_, samplers_.data());
  else if (cpu >= SimdLevel::avx2 && cap != 0)
    avx2::run_code(stage_.code, file_.get(), lanes_in_use, fragment_, samplers_.data());
  else
    baseline::run_code(stage_.code, file_.get(), lanes_in_use, fragment_, samplers_.data());
}

}  // namespace tessera::glsl
