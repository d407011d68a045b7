// Direct volume rendering: the same volume by compositing (DVR) and by maximum-intensity projection, side by side.
#include <filesystem>

#include "gallery.hpp"
#include "tessera/volume/procedural.hpp"
#include "tessera/volume/volume_io.hpp"
#include "tessera/volume/volume_render.hpp"

TESSERA_EXAMPLE(ex63_volume_rendering, "63_volume_rendering", "Direct volume rendering and MIP") {
  using namespace tessera;
  const auto head = gallery.data_file("volumes/headsq_64x64x93_int16le.mhd", "procedural metaballs");
  const bool real = head.has_value();
  const Volume<float> v = real ? to_float(read_volume(head->string())) : make_metaballs(64);
  VolumeRenderOptions o;
  o.width = o.height = 256;
  const Vec3 lo = v.origin(), hi = v.to_world(Vec3(v.dims() - 1)), mid = 0.5 * (lo + hi);
  o.camera.center = mid;
  o.camera.eye = mid + Vec3(0.5, -2.0, 0.4) * glm::length(hi - lo);
  o.camera.up = {0, 0, -1};
  o.camera.fovy = radians(30);
  o.transfer =
      real ? TransferFunction::preset("ct-skin", profile_values(v))
           : TransferFunction({{0.8f, {1, 0.6f, 0.3f}, 0}, {1.2f, {1, 0.9f, 0.7f}, 0.6f}, {3, {1, 1, 1}, 0.9f}});
  const ImageRGB dvr = render_volume(v, o);
  o.mip = true;
  const ImageRGB mip = render_volume(v, o);
  ImageRGB sheet(2 * o.width, o.height);
  for (int y = 0; y < o.height; ++y)
    for (int x = 0; x < o.width; ++x) {
      sheet(x, y) = dvr(x, y);
      sheet(o.width + x, y) = mip(x, y);
    }
  const std::string caption = std::string(real ? "The CT head" : "Metaballs") +
                              ". Left: ray-cast compositing with a transfer function and gradient shading; right: "
                              "maximum-intensity projection.";
  gallery.add("63_volume_rendering.png", sheet,
              real ? caption : examples::stand_in_caption("procedural metaballs", "the CT head", caption));
}
