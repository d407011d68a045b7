# Warnings and sanitizers, applied to Tessera's own targets only.
add_library(tessera_build_flags INTERFACE)
target_compile_options(tessera_build_flags INTERFACE -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor
                                                     -Wno-missing-field-initializers)
if(TESSERA_SANITIZE)
  target_compile_options(tessera_build_flags INTERFACE -fsanitize=address,undefined -fno-omit-frame-pointer
                                                       -fno-sanitize-recover=undefined)
  target_link_options(tessera_build_flags INTERFACE -fsanitize=address,undefined)
  if(TESSERA_BUILD_FUZZ AND CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    # libFuzzer steers by the coverage of the code under test, so the libraries get its instrumentation too.
    target_compile_options(tessera_build_flags INTERFACE -fsanitize=fuzzer-no-link)
  endif()
endif()
install(TARGETS tessera_build_flags EXPORT tesseraTargets)
