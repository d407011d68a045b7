// libFuzzer target for transfer-function files (`tessera volume render --tf FILE`): the first byte picks JSON or CSV,
// the rest is the file. A malformed file must end in tessera::Error; one that loads must give finite colors and
// opacities in [0, 1] everywhere, between its points and beyond them. Anything else is a bug.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "tessera/core/error.hpp"
#include "tessera/volume/volume_render.hpp"

namespace {

void check(const tessera::TransferFunction& tf, float v) {
  const tessera::Vec4f c = tf(v);
  for (int k = 0; k < 4; ++k)
    if (!std::isfinite(c[k])) __builtin_trap();
  if (!(c.w >= 0 && c.w <= 1)) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
  try {
    const tessera::TransferFunction tf = data[0] % 2 ? tessera::TransferFunction::from_json(text, "fuzz.json")
                                                     : tessera::TransferFunction::from_csv(text, "fuzz.csv");
    const auto& points = tf.points();
    for (size_t i = 0; i < points.size(); ++i) {
      check(tf, points[i].value);
      if (i + 1 < points.size()) check(tf, 0.5f * points[i].value + 0.5f * points[i + 1].value);
    }
    for (float v : {-3e38f, -1.0f, 0.0f, 0.5f, 1e3f, 3e38f}) check(tf, v);
  } catch (const tessera::Error&) {
  }
  return 0;
}
