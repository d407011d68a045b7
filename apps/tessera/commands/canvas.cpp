#include "command.hpp"
namespace tessera::cli {
void setup_canvas(CLI::App&, CommonOptions&) {}
}
