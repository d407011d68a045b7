#include "tessera/mesh/measure.hpp"

#include <gtest/gtest.h>

#include <limits>

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

// Issue 24, class 2: a face's area is the length of its vector area, whose squared components overflowed once they
// passed about 1e154 (the box at 1e150 had an infinite area) and underflowed below 1e-154 (zero area at 1e-150).
TEST(Measure, AreaOfHugeAndTinyMeshesIsTheScaledUnitArea) {
  for (const double scale : {1e150, 1e-150, 1e100, 1e-100, 1e-153, 1.0}) {
    PolyMesh box = make_box();  // [-1, 1]^3: area 24
    for (Vec3& p : box.positions) p *= scale;
    EXPECT_NEAR(surface_area(box) / scale / scale, 24.0, 1e-13) << scale;
  }
}

// Issue 24, class 2: about 1e300 the triple products of signed_volume were infinite with both signs and summed to NaN
// (`mesh info --stats` printed volume=-nan). Scaled by a power of two, the box's volume 8 s^3 is exact for s = 2^300,
// close to it for s = 1e100 and 1e-100, and +inf where it passes the largest double.
TEST(Measure, VolumeOfHugeMeshesIsScaledNotNaN) {
  const auto scaled_box = [](double scale) {
    PolyMesh box = make_box();
    for (Vec3& p : box.positions) p *= scale;
    return box;
  };
  EXPECT_EQ(signed_volume(scaled_box(0x1p300)), 0x1p903);
  EXPECT_NEAR(signed_volume(scaled_box(1e100)) / 1e300, 8.0, 1e-13);
  EXPECT_NEAR(signed_volume(scaled_box(1e-100)) / 1e-300, 8.0, 1e-13);
  EXPECT_EQ(signed_volume(scaled_box(1e300)), std::numeric_limits<double>::infinity());
}

}  // namespace
}  // namespace tessera
