// tessera trace: placeholder until its module lands.
#include "command.hpp"

namespace tessera::cli {

void setup_trace(CLI::App&, CommonOptions&) {}

}  // namespace tessera::cli
