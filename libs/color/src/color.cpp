#include "tessera/math/types.hpp"
