// An outside program against the installed Tessera: the README's ten-line example, then checks of what it wrote.
// Run in a scratch folder; exits 0 when the results are right.
#include <cstdio>

#include "tessera/image/image_io.hpp"
#include "tessera/mesh/mesh_io.hpp"
#include "tessera/mesh/primitives.hpp"
#include "tessera/raster2d/canvas.hpp"
#include "tessera/subdiv/subdivide.hpp"

int main() {
  // --- the README example ---
  tessera::Canvas canvas(400, 400);  // Processing's size(400, 400)
  canvas.background({1, 1, 1, 1});
  canvas.fill({1.0f, 150 / 255.0f, 150 / 255.0f, 1});  // the notes' pink
  canvas.push_matrix();
  canvas.translate(200, 200);
  canvas.rotate(0.3);
  canvas.rect(-50, -50, 100, 100);
  canvas.pop_matrix();
  canvas.save("square.png");
  tessera::write_mesh("cube3.obj", tessera::catmull_clark_subdivide(tessera::make_cube(), 3));
  // --- checks ---
  const tessera::ImageRGBA square = tessera::read_image("square.png");
  const tessera::PolyMesh cube3 = tessera::read_mesh("cube3.obj");
  const glm::vec4 center = square(200, 200), corner = square(5, 5);
  const bool ok = square.width() == 400 && center.y < 0.6f && corner.y == 1.0f && cube3.face_count() == 6 * 64;
  std::printf("consumer: %s\n", ok ? "ok" : "wrong");
  return ok ? 0 : 1;
}
