// The executor built for AVX2 and FMA (CMakeLists.txt gives this file -mavx2 -mfma): eight lanes per instruction.
#define TESSERA_GLSL_ISA avx2
#include "execute_impl.hpp"
