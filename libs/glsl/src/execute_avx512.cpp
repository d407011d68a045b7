// The executor built for AVX-512 (CMakeLists.txt gives this file -mavx512f -mavx512vl -mavx512bw -mavx512dq -mfma):
// sixteen lanes per instruction.
#define TESSERA_GLSL_ISA avx512
#include "execute_impl.hpp"
