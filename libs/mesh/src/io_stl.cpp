// STL reader and writer (binary: 80-byte header, triangle count, 50 bytes per triangle; ASCII: solid/facet/vertex).
#include <ostream>

#include "io_common.hpp"
#include "tessera/mesh/mesh_io.hpp"
#include "tessera/mesh/normals.hpp"
#include "tessera/mesh/soup.hpp"
#include "tessera/mesh/triangulate.hpp"

namespace tessera {
namespace {
using mesh_io::TextCursor;

constexpr size_t kHeaderBytes = 84, kTriangleBytes = 50;

PolygonSoup read_binary(std::string_view data, const std::string& name, mesh_io::ByteProgress& bytes) {
  const auto count = mesh_io::load_scalar<uint32_t>(data.data() + 80, false);
  PolygonSoup soup;
  soup.points.reserve(3 * size_t(count));
  soup.face_offsets.reserve(size_t(count) + 1);
  for (size_t t = 0; t < count; ++t) {
    const char* p = data.data() + kHeaderBytes + t * kTriangleBytes + 12;  // skip the stored normal
    bytes.at(p);
    std::array<Vec3, 3> corners;
    for (int i = 0; i < 9; ++i) {
      const float v = mesh_io::load_scalar<float>(p + 4 * i, false);
      if (!std::isfinite(v))
        mesh_io::fail_at_byte(name, (p + 4 * i) - data.data(), "expected a finite vertex coordinate");
      corners[size_t(i / 3)][i % 3] = v;
    }
    soup.add_face(corners);
  }
  return soup;
}

void expect(TextCursor& in, std::string_view word) {
  in.skip_empty_lines();
  const std::string_view got = in.token();
  if (got != word)
    in.fail(fmt::format("expected '{}', got '{}'", word, got.empty() ? in.preview() : printable(got, 40)));
}

PolygonSoup read_ascii(std::string_view data, const std::string& name, mesh_io::ByteProgress& bytes) {
  TextCursor in(data, name, false);
  in.set_progress(&bytes);
  PolygonSoup soup;
  in.skip_empty_lines();
  while (!in.at_end()) {
    expect(in, "solid");
    in.next_line();  // the solid's name
    while (true) {
      in.skip_empty_lines();
      if (in.at_end()) in.fail("expected 'facet' or 'endsolid', got end of file");
      const std::string_view key = in.token();
      if (key == "endsolid") {
        in.next_line();
        break;
      }
      if (key != "facet") in.fail(fmt::format("expected 'facet' or 'endsolid', got '{}'", printable(key, 40)));
      expect(in, "normal");
      for (int i = 0; i < 3; ++i) in.number("a facet normal component");
      in.end_line("the facet normal");
      expect(in, "outer");
      expect(in, "loop");
      in.end_line("'outer loop'");
      std::array<Vec3, 3> corners;
      for (Vec3& c : corners) {
        expect(in, "vertex");
        for (int i = 0; i < 3; ++i) c[i] = in.number("a vertex coordinate");
        in.end_line("a vertex");
      }
      expect(in, "endloop");
      in.end_line("'endloop'");
      expect(in, "endfacet");
      in.end_line("'endfacet'");
      soup.add_face(corners);
    }
    in.skip_empty_lines();
  }
  return soup;
}

}  // namespace

PolyMesh read_stl(std::string_view data, const std::string& name, Progress* progress) {
  const bool binary_size =
      data.size() >= kHeaderBytes &&
      (data.size() - kHeaderBytes) / kTriangleBytes == mesh_io::load_scalar<uint32_t>(data.data() + 80, false) &&
      (data.size() - kHeaderBytes) % kTriangleBytes == 0;
  size_t start = 0;
  while (start < data.size() && std::isspace(static_cast<unsigned char>(data[start]))) ++start;
  const bool ascii = !binary_size && data.substr(start, 5) == "solid";
  if (!binary_size && !ascii) {
    if (data.size() < kHeaderBytes)
      mesh_io::fail_at_byte(name, long(data.size()), "expected an 84-byte binary STL header or 'solid'");
    const auto count = mesh_io::load_scalar<uint32_t>(data.data() + 80, false);
    mesh_io::fail_at_byte(name, long(data.size()),
                          fmt::format("expected {} bytes for {} binary STL triangles (84 + 50 n), the file has {}",
                                      kHeaderBytes + size_t(count) * kTriangleBytes, count, data.size()));
  }
  mesh_io::ByteProgress bytes(progress, data);
  PolyMesh mesh = weld(ascii ? read_ascii(data, name, bytes) : read_binary(data, name, bytes));
  bytes.finish();
  return mesh;
}

void write_stl(std::ostream& out, const PolyMesh& mesh, bool binary) {
  const PolyMesh tris = triangulate(mesh);
  const std::vector<Vec3> normals = face_normals(tris);
  if (!binary) {
    mesh_io::BufferedWriter w(out);
    w.print("solid tessera\n");
    for (size_t f = 0; f < tris.face_count(); ++f) {
      w.print("facet normal {} {} {}\nouter loop\n", normals[f].x, normals[f].y, normals[f].z);
      for (uint32_t v : tris.face(f))
        w.print("vertex {} {} {}\n", tris.positions[v].x, tris.positions[v].y, tris.positions[v].z);
      w.print("endloop\nendfacet\n");
    }
    w.print("endsolid tessera\n");
    return;
  }
  std::string bytes(80, '\0');
  const std::string_view title = "binary STL written by tessera";
  std::copy(title.begin(), title.end(), bytes.begin());
  mesh_io::store_le(bytes, uint32_t(tris.face_count()));
  for (size_t f = 0; f < tris.face_count(); ++f) {
    for (int i = 0; i < 3; ++i) mesh_io::store_le(bytes, float(normals[f][i]));
    for (uint32_t v : tris.face(f))
      for (int i = 0; i < 3; ++i) mesh_io::store_le(bytes, float(tris.positions[v][i]));
    mesh_io::store_le(bytes, uint16_t(0));
  }
  out.write(bytes.data(), std::streamsize(bytes.size()));
}

}  // namespace tessera
