// OFF reader and writer (Geomview's Object File Format: [ST][C][N]OFF, counts, vertex lines, face lines).
#include <ostream>

#include "io_common.hpp"
#include "tessera/mesh/mesh_io.hpp"

namespace tessera {
namespace {
using mesh_io::TextCursor;

/// What the header keyword announces on each vertex line after x y z.
struct OffLayout {
  bool texture = false, color = false, normal = false;
};

OffLayout parse_keyword(TextCursor& in, std::string_view key) {
  OffLayout layout;
  std::string_view k = key;
  const auto take = [&](std::string_view prefix) {
    if (k.substr(0, prefix.size()) != prefix) return false;
    k.remove_prefix(prefix.size());
    return true;
  };
  layout.texture = take("ST");
  layout.color = take("C");
  layout.normal = take("N");
  if (k != "OFF")
    in.fail(fmt::format(
        "expected the keyword OFF (optionally ST, C, N prefixes; 4OFF and nOFF are not supported), got '{}'",
        printable(key, 40)));
  return layout;
}

/// Reads one count of the header; each must fit the bytes left (a vertex or face line takes at least 6 bytes).
size_t parse_count(TextCursor& in, const char* what) {
  in.skip_empty_lines();
  const long long n = in.integer(what);
  if (n < 0 || size_t(n) > in.remaining() / 2 || n > INT32_MAX)
    in.fail(fmt::format("{} {} is negative or larger than the rest of the file can hold", what, n));
  return size_t(n);
}

}  // namespace

PolyMesh read_off(std::string_view data, const std::string& name, Progress* progress) {
  TextCursor in(data, name, true);
  mesh_io::ByteProgress bytes(progress, data);
  in.set_progress(&bytes);
  in.skip_empty_lines();
  const OffLayout layout = parse_keyword(in, in.token());
  const size_t nv = parse_count(in, "a vertex count");
  const size_t nf = parse_count(in, "a face count");
  double edges;
  in.try_number(edges);  // the edge count is optional and unused
  in.end_line("the counts");

  PolyMesh mesh;
  mesh.positions.reserve(nv);
  for (size_t v = 0; v < nv; ++v) {
    in.skip_empty_lines();
    Vec3 p;
    for (int i = 0; i < 3; ++i) p[i] = in.number("a vertex coordinate");
    mesh.positions.push_back(p);
    if (layout.normal) {
      Vec3 n;
      for (int i = 0; i < 3; ++i) n[i] = in.number("a normal component");
      mesh.normals.push_back(n);
    }
    // Colors: 3 or 4 numbers (floats in [0, 1] or integers 0..255); the texture pair comes last.
    std::array<double, 6> rest{};
    size_t n_rest = 0;
    while (n_rest < rest.size() && in.try_number(rest[n_rest])) ++n_rest;
    if (layout.texture && n_rest < 2) in.fail("expected the texture coordinates s t");
    const size_t n_color = n_rest - (layout.texture ? 2 : 0);
    if (layout.color) {
      if (n_color != 3 && n_color != 4) in.fail(fmt::format("expected a color r g b [a], got {} numbers", n_color));
      const double scale = rest[0] > 1 || rest[1] > 1 || rest[2] > 1 ? 1.0 / 255.0 : 1.0;
      mesh.colors.emplace_back(rest[0] * scale, rest[1] * scale, rest[2] * scale);
    } else if (n_color != 0) {
      in.fail(fmt::format("unexpected number after the vertex (the header is '{}OFF' style without colors)",
                          layout.texture ? "ST" : ""));
    }
    if (layout.texture) mesh.uvs.emplace_back(rest[n_rest - 2], rest[n_rest - 1]);
    in.end_line("a vertex");
  }
  mesh.face_offsets.reserve(nf + 1);
  for (size_t f = 0; f < nf; ++f) {
    in.skip_empty_lines();
    const long long n = in.integer("a face vertex count");
    if (n < 3 || size_t(n) > in.remaining() / 2)
      in.fail(fmt::format("a face needs 3 or more vertices (that fit the file), got {}", n));
    for (long long i = 0; i < n; ++i) {
      const long long v = in.integer("a vertex index");
      if (v < 0 || size_t(v) >= nv) in.fail(fmt::format("vertex index {} is out of range (0..{})", v, long(nv) - 1));
      mesh.face_vertices.push_back(uint32_t(v));
    }
    mesh.face_offsets.push_back(uint32_t(mesh.face_vertices.size()));
    in.next_line();  // a face color may follow; it is ignored
  }
  in.skip_empty_lines();
  if (!in.at_end()) in.fail(fmt::format("expected the end of the file after {} faces, got '{}'", nf, in.preview()));
  bytes.finish();
  return mesh;
}

void write_off(std::ostream& out, const PolyMesh& mesh) {
  const size_t nv = mesh.vertex_count();
  const bool colors = !mesh.colors.empty() && mesh.colors.size() == nv;
  const bool normals = !mesh.normals.empty() && mesh.normals.size() == nv;
  const bool uvs = !mesh.uvs.empty() && mesh.uvs.size() == nv;
  mesh_io::BufferedWriter w(out);
  w.print("{}{}{}OFF\n{} {} 0\n", uvs ? "ST" : "", colors ? "C" : "", normals ? "N" : "", nv, mesh.face_count());
  for (size_t v = 0; v < nv; ++v) {
    const Vec3& p = mesh.positions[v];
    w.print("{} {} {}", p.x, p.y, p.z);
    if (normals) w.print(" {} {} {}", mesh.normals[v].x, mesh.normals[v].y, mesh.normals[v].z);
    if (colors) w.print(" {} {} {} 1", mesh.colors[v].x, mesh.colors[v].y, mesh.colors[v].z);
    if (uvs) w.print(" {} {}", mesh.uvs[v].x, mesh.uvs[v].y);
    w.print("\n");
  }
  for (size_t f = 0; f < mesh.face_count(); ++f) {
    w.print("{}", mesh.face_size(f));
    for (uint32_t v : mesh.face(f)) w.print(" {}", v);
    w.print("\n");
  }
}

}  // namespace tessera
