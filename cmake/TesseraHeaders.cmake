# The generated public headers, on the umbrella target tessera_all (tessera::tessera) and installed next to the
# modules' headers: tessera/version.hpp (project(VERSION) and the checkout's `git describe`, cmake/version.hpp.in)
# and tessera/tessera.hpp (every module's public headers, cmake/tessera.hpp.in). Included after tessera_all exists.
set(generated_include ${PROJECT_BINARY_DIR}/include)

# The commit, at configure time; "unknown" outside a git checkout of Tessera itself (not a parent project's).
set(TESSERA_GIT_HASH unknown)
find_package(Git QUIET)
if(GIT_FOUND AND EXISTS ${PROJECT_SOURCE_DIR}/.git)
  execute_process(COMMAND ${GIT_EXECUTABLE} describe --always --dirty WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
                  OUTPUT_VARIABLE described OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE git_result ERROR_QUIET)
  if(git_result EQUAL 0 AND described)
    set(TESSERA_GIT_HASH ${described})
  endif()
endif()
configure_file(${CMAKE_CURRENT_LIST_DIR}/version.hpp.in ${generated_include}/tessera/version.hpp @ONLY)

configure_file(${CMAKE_CURRENT_LIST_DIR}/tessera.hpp.in ${generated_include}/tessera/tessera.hpp @ONLY)

target_include_directories(tessera_all INTERFACE $<BUILD_INTERFACE:${generated_include}>
                                                 $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
install(FILES ${generated_include}/tessera/version.hpp ${generated_include}/tessera/tessera.hpp
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/tessera)

if(TESSERA_BUILD_TESTS)
  # The umbrella header compiles alone, and the version macros agree with project(VERSION).
  add_executable(umbrella_header_test ${PROJECT_SOURCE_DIR}/tests/install/umbrella_main.cpp)
  target_link_libraries(umbrella_header_test PRIVATE tessera_all tessera_build_flags)
  target_compile_definitions(umbrella_header_test PRIVATE EXPECTED_VERSION="${PROJECT_VERSION}")
  add_test(NAME umbrella.header_alone COMMAND umbrella_header_test)
  set_tests_properties(umbrella.header_alone PROPERTIES LABELS install)
  # The umbrella lists every public header of every module (they are listed by hand, not globbed).
  add_test(NAME umbrella.lists_every_header COMMAND ${PROJECT_SOURCE_DIR}/tests/install/umbrella_lists_every_header.sh)
  set_tests_properties(umbrella.lists_every_header PROPERTIES LABELS install)
endif()
