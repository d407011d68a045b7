#include "tessera/image/image.hpp"
