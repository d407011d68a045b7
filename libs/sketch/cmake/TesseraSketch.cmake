# tessera_add_sketch(<name> <file.cpp>...)
#
# Builds the program <name> from a sketch: a class derived from tessera::Sketch and `TESSERA_SKETCH_MAIN(Class)`
# (tessera/sketch/runner.hpp). The program takes the runner's flags, as `tessera sketch` does: --frames N,
# --seconds S, --fps F, -o out.gif|out.mp4|dir/|picture.png, --size WxH, --window/--headless, --input FILE,
# --threads N, --seed N, --srgb, --stats (docs/sketch.md). Installed with the package: find_package(tessera) gives it.
function(tessera_add_sketch name)
  if(NOT ARGN)
    message(FATAL_ERROR "tessera_add_sketch(${name}): name the sketch's source file(s)")
  endif()
  add_executable(${name} ${ARGN})
  target_link_libraries(${name} PRIVATE tessera::sketch)
  target_compile_features(${name} PRIVATE cxx_std_20)
endfunction()
