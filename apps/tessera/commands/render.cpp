// tessera render: placeholder until its module lands.
#include "command.hpp"

namespace tessera::cli {

void setup_render(CLI::App&, CommonOptions&) {}

}  // namespace tessera::cli
