#include "tessera/mesh/measure.hpp"

#include <gtest/gtest.h>

#include "tessera/mesh/primitives.hpp"

namespace tessera {
namespace {

TEST(Measure, BoxAreaVolumeAndBounds) {
  const PolyMesh box = make_box();
  EXPECT_DOUBLE_EQ(surface_area(box), 24.0);
  EXPECT_DOUBLE_EQ(signed_volume(box), 8.0);
  const Bounds3 b = bounding_box(box);
  EXPECT_EQ(b.lo, Vec3(-1));
  EXPECT_EQ(b.hi, Vec3(1));
  EXPECT_TRUE(bounding_box(PolyMesh{}).empty());
}

TEST(Measure, VolumeIsIndependentOfTheOriginForClosedMeshes) {
  PolyMesh box = make_box();
  for (Vec3& p : box.positions) p += Vec3(5, -3, 2);
  EXPECT_NEAR(signed_volume(box), 8.0, 1e-12);
}

}  // namespace
}  // namespace tessera
