// tessera bench: placeholder until its module lands.
#include "command.hpp"

namespace tessera::cli {

void setup_bench(CLI::App&, CommonOptions&) {}

}  // namespace tessera::cli
