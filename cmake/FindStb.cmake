# Debian's libstb-dev ships the stb headers under <stb/...>; Tessera compiles the implementations it uses itself
# (libs/image/src/stb.cpp), so only the headers are needed.
find_path(STB_INCLUDE_DIR NAMES stb/stb_image.h)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(Stb REQUIRED_VARS STB_INCLUDE_DIR)
if(Stb_FOUND AND NOT TARGET Stb::stb)
  add_library(Stb::stb INTERFACE IMPORTED)
  set_target_properties(Stb::stb PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${STB_INCLUDE_DIR}")
endif()
