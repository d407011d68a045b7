#include "tessera/image/metrics.hpp"
