#include "command.hpp"
namespace tessera::cli {
void setup_curve(CLI::App&, CommonOptions&) {}
}
