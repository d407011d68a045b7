// tessera raster: placeholder until its module lands.
#include "command.hpp"

namespace tessera::cli {

void setup_raster(CLI::App&, CommonOptions&) {}

}  // namespace tessera::cli
