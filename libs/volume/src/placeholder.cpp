#include "tessera/mesh/poly_mesh.hpp"
