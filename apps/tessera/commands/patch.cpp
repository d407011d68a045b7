#include "command.hpp"
namespace tessera::cli {
void setup_patch(CLI::App&, CommonOptions&) {}
}
