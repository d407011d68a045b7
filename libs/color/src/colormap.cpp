#include "tessera/color/colormap.hpp"

#include <algorithm>
#include <cmath>

namespace tessera {

Vec3f heat_color(float x) {
  x = std::clamp(x, 0.0f, 1.0f);
  auto tent = [x](float center) { return std::clamp(1.5f - std::abs(4.0f * x - center), 0.0f, 1.0f); };
  return {tent(3.0f), tent(2.0f), tent(1.0f)};
}

}  // namespace tessera
