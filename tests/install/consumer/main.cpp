// Uses a few modules through the installed headers and libraries; exits 0 when the results are right.
#include <cmath>
#include <cstdio>

#include "tessera/image/image.hpp"
#include "tessera/math/matrix_stack.hpp"
#include "tessera/math/transform.hpp"

int main() {
  tessera::MatrixStack3 stack;
  stack.push();
  stack.multiply(tessera::translate(1, 2, 3));
  const tessera::Vec3 p = tessera::transform_point(stack.top(), {0, 0, 0});
  stack.pop();
  tessera::ImageRGB image(4, 3, {0.5f, 0.25f, 1.0f});
  const bool ok = p == tessera::Vec3(1, 2, 3) && image.width() == 4 && image(3, 2).z == 1.0f;
  std::printf("consumer: %s\n", ok ? "ok" : "wrong");
  return ok ? 0 : 1;
}
