#include "command.hpp"
namespace tessera::cli {
void setup_color(CLI::App&, CommonOptions&) {}
}
