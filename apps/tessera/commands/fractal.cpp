#include "command.hpp"
namespace tessera::cli {
void setup_fractal(CLI::App&, CommonOptions&) {}
}
