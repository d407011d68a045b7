# tessera_add_module(<name> SOURCES <src>... [DEPS <module>...] [LIBS <external target>...])
#
# Creates the library target tessera_<name> (alias tessera::<name>) from libs/<name>/, with libs/<name>/include as its
# only own include root. DEPS must name Tessera modules that were added before: a missing one stops the configure, so
# the layer order of DESIGN.md cannot be broken and cycles cannot be written.
function(tessera_add_module name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS;LIBS" ${ARGN})
  if(NOT ARG_SOURCES)
    message(FATAL_ERROR "tessera_add_module(${name}): SOURCES is required")
  endif()
  foreach(dep IN LISTS ARG_DEPS)
    if(NOT TARGET tessera_${dep})
      message(FATAL_ERROR "tessera_add_module(${name}): dependency '${dep}' is not defined yet "
                          "(modules must be added in layer order, see docs/architecture.md)")
    endif()
  endforeach()
  set(target tessera_${name})
  add_library(${target} ${ARG_SOURCES})
  add_library(tessera::${name} ALIAS ${target})
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${name} OUTPUT_NAME tessera_${name})
  target_include_directories(${target} PUBLIC $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
                                              $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>
                                       PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/src)
  list(TRANSFORM ARG_DEPS PREPEND tessera_ OUTPUT_VARIABLE dep_targets)
  target_link_libraries(${target} PUBLIC ${dep_targets} ${ARG_LIBS} PRIVATE $<BUILD_INTERFACE:tessera_build_flags>)
  if(TESSERA_SANITIZE)
    target_link_libraries(${target} INTERFACE $<BUILD_INTERFACE:tessera_build_flags>)
  endif()
  install(TARGETS ${target} EXPORT tesseraTargets)
  install(DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  set(TESSERA_MODULES ${TESSERA_MODULES} ${target} CACHE INTERNAL "Tessera module targets")
endfunction()

# tessera_share_pch(<target> <group> <header>...)
#
# One precompiled header for a group of targets: the group's first target makes it from the headers, the others
# reuse it. GCC uses it where the macros and target flags agree (those of one build are the same for all the group's
# targets) and otherwise silently parses the headers as before. Where it uses it, GCC also restores the optimization
# options the header was made with (-ffp-contract among them), so no module passes such an option on to its users:
# raster3d's -ffp-contract=off is private (its vector kernels are compiled in its own sources, its users' code has no
# FMA to contract).
function(tessera_share_pch target group)
  get_property(donor GLOBAL PROPERTY TESSERA_PCH_${group})
  if(donor)
    target_precompile_headers(${target} REUSE_FROM ${donor})
  else()
    target_precompile_headers(${target} PRIVATE ${ARGN})
    set_property(GLOBAL PROPERTY TESSERA_PCH_${group} ${target})
  endif()
endfunction()

# tessera_add_tests(<module> SOURCES <name>_test.cpp... [DEPS <target>...])
#
# One GoogleTest executable per module (fewer links on a 2-core machine); each TEST becomes its own ctest entry,
# labelled `unit`.
# Tests run with the source tree as working directory and TESSERA_SHARED_DATA pointing at ../shared/data.
function(tessera_add_tests module)
  if(NOT TESSERA_BUILD_TESTS)
    return()
  endif()
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  set(target ${module}_tests)
  add_executable(${target} ${ARG_SOURCES})
  target_link_libraries(${target} PRIVATE tessera_${module} ${ARG_DEPS} GTest::gtest GTest::gmock GTest::gtest_main
                                          tessera_build_flags)
  target_compile_definitions(${target} PRIVATE TESSERA_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
                                               TESSERA_SHARED_DATA="${TESSERA_SHARED_DATA}")
  # GoogleTest, GoogleMock and the usual standard headers, parsed once for all the test programs instead of about a
  # second of each of the ~70 test files, in both CI builds.
  tessera_share_pch(${target} tests <gtest/gtest.h> <gmock/gmock.h> <algorithm> <cmath> <filesystem> <functional>
                    <string> <vector>)
  # Test names carry the module ("mesh.CornerTable.Swing"): select a module with `ctest -R '^mesh\.'`.
  gtest_discover_tests(${target} WORKING_DIRECTORY ${PROJECT_SOURCE_DIR} DISCOVERY_MODE PRE_TEST
                       TEST_PREFIX "${module}." PROPERTIES LABELS unit)
  add_dependencies(unit_tests ${target})
endfunction()

# `unit_tests` builds every module's test program (the sanitizer run builds and runs only these).
if(TESSERA_BUILD_TESTS AND NOT TARGET unit_tests)
  add_custom_target(unit_tests)
  # Fixtures several modules' tests share (tests/support/tessera_test/: a scratch folder per test), by DEPS.
  add_library(tessera_test_support INTERFACE)
  target_include_directories(tessera_test_support INTERFACE ${PROJECT_SOURCE_DIR}/tests/support)
endif()

# ../shared/data beside the checkout holds the optional real data sets; tests skip cleanly without it.
get_filename_component(_shared_data "${PROJECT_SOURCE_DIR}/../shared/data" ABSOLUTE)
set(TESSERA_SHARED_DATA "${_shared_data}" CACHE PATH "Folder with the optional shared data sets")
