// libFuzzer target for scene files and the two renderers behind them: parses the input as scene JSON (files named in it
// are looked up in a folder that does not exist), then ray traces it and rasterizes it with shadow volumes and with
// shadow maps of 32 x 32 (the default 2048 x 2048 would take most of each run), at 8 x 6 pixels with at most 4 samples
// and depth 4.
// tessera::Error is the expected outcome for a bad scene; anything else (a crash, another exception, a sanitizer
// report, a hang) is a bug, and so is a pixel that is NaN or negative (colors in a scene are non-negative; an absurdly
// bright one may overflow to infinity). Seeds: fuzz/corpus/scene/ and the built-in scenes (scenes/).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "tessera/core/error.hpp"
#include "tessera/scene/raster.hpp"
#include "tessera/scene/scene.hpp"
#include "tessera/scene/trace.hpp"

namespace {

void check_pixels(const tessera::ImageRGB& image) {
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x)
      for (int c = 0; c < 3; ++c) {
        const float v = image(x, y)[c];
        if (std::isnan(v) || v < 0) __builtin_trap();
      }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace tessera;
  try {
    const Scene scene =
        parse_scene(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.json", "/nonexistent/fuzz");
    RenderSettings settings = render_settings(scene);
    settings.width = 8;
    settings.height = 6;
    settings.samples = std::min(settings.samples, 4);
    settings.max_depth = std::min(settings.max_depth, 4);
    settings.progress = false;
    check_pixels(render(to_ray_scene(scene), settings));
    check_pixels(rasterize_scene(scene, 8, 6, RasterShadows::volumes));
    check_pixels(rasterize_scene(scene, 8, 6, RasterShadows::map, 32));
  } catch (const Error&) {
  }
  return 0;
}
