// Smoothing before and after: a noisy sphere, then 20 steps of the notes' uniform Laplacian, of cotangent-weighted
// Laplacian, and of Taubin's lambda|mu smoothing. All four are drawn with the same camera, so the Laplacian's
// shrinkage shows as a smaller ball while Taubin's keeps its size.
#include <fmt/format.h>

#include "gallery.hpp"
#include "mesh_view.hpp"
#include "tessera/core/rng.hpp"
#include "tessera/mesh/measure.hpp"
#include "tessera/mesh/primitives.hpp"
#include "tessera/mesh/smoothing.hpp"
#include "tessera/mesh/triangulate.hpp"

TESSERA_EXAMPLE(ex32_smoothing, "32_smoothing", "Laplacian and Taubin smoothing") {
  using namespace tessera;
  PolyMesh noisy = triangulate(make_quad_sphere(10));
  Rng rng(32);
  for (Vec3& p : noisy.positions) p *= 1.0 + rng.uniform(-0.04, 0.04);
  const double v0 = signed_volume(noisy);

  examples::MeshViewOptions options;
  options.width = options.height = 300;
  Camera camera;
  camera.eye = 3.2 * glm::normalize(Vec3(1, 0.8, 1.6));
  camera.fovy = radians(40);
  camera.near = 1.0;
  camera.far = 6.0;
  options.camera = camera;

  ImageRGB sheet(4 * options.width, options.height, Vec3f(1.0f));
  std::string caption = "A noisy sphere (left), then 20 steps of";
  const std::pair<const char*, SmoothingMethod> methods[] = {{"uniform Laplacian", SmoothingMethod::laplacian},
                                                             {"cotangent Laplacian", SmoothingMethod::cotangent},
                                                             {"Taubin lambda|mu", SmoothingMethod::taubin}};
  const auto paste = [&](const ImageRGB& tile, int column) {
    for (int y = 0; y < tile.height(); ++y)
      for (int x = 0; x < tile.width(); ++x) sheet(column * options.width + x, y) = tile(x, y);
  };
  paste(examples::render_mesh(noisy, options), 0);
  for (int i = 0; i < 3; ++i) {
    PolyMesh mesh = noisy;
    smooth(mesh, {methods[i].second, 20});
    paste(examples::render_mesh(mesh, options), i + 1);
    caption += fmt::format("{} {} (volume {:+.1f}%)",
                           i == 0   ? ""
                           : i == 2 ? ", and"
                                    : ",",
                           methods[i].first, 100.0 * (signed_volume(mesh) / v0 - 1.0));
  }
  gallery.add("32_smoothing.png", sheet,
              caption +
                  ", all seen by the same camera: the Laplacian shrinks the ball, "
                  "Taubin's alternating steps keep its size.");
}
