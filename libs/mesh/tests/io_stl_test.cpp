#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sstream>

#include "tessera/core/error.hpp"
#include "tessera/mesh/measure.hpp"
#include "tessera/mesh/mesh_io.hpp"
#include "tessera/mesh/primitives.hpp"
#include "tessera/mesh/topology.hpp"

namespace tessera {
namespace {

using ::testing::HasSubstr;

std::string error_of(std::string_view data) {
  try {
    read_stl(data, "t.stl");
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "no error";
}

TEST(Stl, BinaryAndAsciiRoundTripsWeldIntoAClosedMesh) {
  const PolyMesh box = make_box();
  for (bool binary : {true, false}) {
    SCOPED_TRACE(binary ? "binary" : "ascii");
    std::ostringstream out;
    write_stl(out, box, binary);
    if (binary) {
      EXPECT_EQ(out.str().size(), 84u + 12u * 50u);
    }
    const PolyMesh back = read_stl(out.str(), "box.stl");
    EXPECT_EQ(back.vertex_count(), 8u);  // welded
    EXPECT_EQ(back.face_count(), 12u);
    const TopologyReport r = analyze_topology(back);
    EXPECT_TRUE(r.closed());
    EXPECT_TRUE(r.oriented());
    EXPECT_NEAR(signed_volume(back), 8.0, 1e-6);
  }
}

TEST(Stl, AsciiWithIndentationAndSeveralSolids) {
  const std::string one =
      "solid a\n  facet normal 0 0 1\n    outer loop\n      vertex 0 0 0\n      vertex 1 0 0\n"
      "      vertex 0 1 0\n    endloop\n  endfacet\nendsolid a\n";
  EXPECT_EQ(read_stl(one + one, "t.stl").face_count(), 2u);
}

TEST(Stl, ErrorsNameLineOrByte) {
  EXPECT_THAT(error_of("solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0\n"),
              HasSubstr("t.stl:5: expected a vertex coordinate"));
  EXPECT_THAT(error_of("solid a\nfacet normal 0 0 1\nouter lop\n"), HasSubstr("t.stl:3: expected 'loop'"));
  EXPECT_THAT(error_of("solid a\nfacet normal 0 0 1\n"), HasSubstr("expected 'outer'"));
  std::string binary(84, '\0');
  binary[80] = char(0xFF);  // claims 255 triangles, has none
  EXPECT_THAT(error_of(binary), HasSubstr("t.stl: byte offset 84: expected 12834 bytes"));
  EXPECT_THAT(error_of("abc"), HasSubstr("expected an 84-byte binary STL header"));
  std::string nan_tri(84 + 50, '\0');
  nan_tri[80] = 1;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(nan_tri.data() + 84 + 12 + 4, &nan, 4);
  EXPECT_THAT(error_of(nan_tri), HasSubstr("byte offset 100: expected a finite vertex coordinate"));
}

}  // namespace
}  // namespace tessera
