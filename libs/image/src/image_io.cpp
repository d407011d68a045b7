#include "tessera/image/image_io.hpp"
