#include "command.hpp"
namespace tessera::cli {
void setup_volume(CLI::App&, CommonOptions&) {}
}
