#include "command.hpp"
namespace tessera::cli {
void setup_mesh_subdivide(CLI::App&, CommonOptions&) {}
}
