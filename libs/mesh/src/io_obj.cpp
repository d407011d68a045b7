// OBJ reader and writer. The reader walks one memory buffer with a hand-written cursor (std::from_chars numbers, no
// stream per line): about 10x less work per line than a tokenizing stream parser.
#include <algorithm>
#include <array>
#include <bit>
#include <ostream>
#include <unordered_map>

#include "bit_key.hpp"
#include "io_common.hpp"
#include "tessera/mesh/mesh_io.hpp"

namespace tessera {
namespace {

using mesh_io::BufferedWriter;
using mesh_io::TextCursor;

/// Statements of the OBJ specification that carry nothing a PolyMesh holds (groups, materials, smoothing groups,
/// free-form geometry, lines, points, rendering attributes). They are skipped; anything else unknown is an error.
bool is_ignored_statement(std::string_view key) {
  static constexpr std::array<std::string_view, 36> kIgnored{
      "o",         "g",     "s",     "mg",       "usemtl",   "mtllib", "usemap", "maplib", "shadow_obj",
      "trace_obj", "lod",   "bevel", "c_interp", "d_interp", "cstype", "deg",    "bmat",   "step",
      "curv",      "curv2", "surf",  "parm",     "trim",     "hole",   "scrv",   "sp",     "end",
      "con",       "call",  "csh",   "vp",       "ctech",    "stech",  "l",      "p",      "res"};
  return std::find(kIgnored.begin(), kIgnored.end(), key) != kIgnored.end();
}

/// Per-corner references to a vt or vn list, filled lazily (most files have none): -1 = no reference.
struct CornerRefs {
  std::vector<int32_t> refs;
  bool any = false;

  void add(size_t corner, int32_t ref) {
    if (ref >= 0 && !any) {
      any = true;
      refs.resize(corner, -1);
    }
    if (any) refs.push_back(ref);
  }
};

/// The number of lines starting with v, vt, vn and f (bounded by the size of the data, so safe to reserve).
struct LineCounts {
  size_t v = 0, vt = 0, vn = 0, f = 0;
};

LineCounts count_lines(std::string_view data) {
  LineCounts n;
  const char* p = data.data();
  const char* end = p + data.size();
  while (p < end) {
    if (end - p >= 2) {
      if (p[0] == 'v' && (p[1] == ' ' || p[1] == '\t')) ++n.v;
      if (p[0] == 'f' && (p[1] == ' ' || p[1] == '\t')) ++n.f;
      if (end - p >= 3 && p[0] == 'v' && (p[2] == ' ' || p[2] == '\t')) {
        n.vt += p[1] == 't';
        n.vn += p[1] == 'n';
      }
    }
    const void* nl = std::memchr(p, '\n', size_t(end - p));
    p = nl == nullptr ? end : static_cast<const char*>(nl) + 1;
  }
  return n;
}

/// A 1-based (or negative, relative) OBJ index into a list of `count` items, as a 0-based index.
int32_t resolve_index(TextCursor& in, long long index, size_t count, const char* what) {
  if (index > 0 && size_t(index) <= count) return int32_t(index - 1);
  if (index < 0 && size_t(-index) <= count) return int32_t(count - size_t(-index));
  in.fail(fmt::format("{} index {} is out of range ({} defined so far)", what, index, count));
}

void parse_face(TextCursor& in, PolyMesh& mesh, size_t uv_count, size_t normal_count, CornerRefs& uv_refs,
                CornerRefs& normal_refs) {
  const size_t first = mesh.face_vertices.size();
  while (!in.at_line_end()) {
    const size_t corner = mesh.face_vertices.size();
    mesh.face_vertices.push_back(
        uint32_t(resolve_index(in, in.integer("a vertex index"), mesh.positions.size(), "vertex")));
    int32_t uv = -1, normal = -1;
    if (in.peek() == '/') {
      in.advance();
      if (in.peek() != '/')
        uv = resolve_index(in, in.integer("a texture coordinate index", true), uv_count, "texture coordinate");
      if (in.peek() == '/') {
        in.advance();
        normal = resolve_index(in, in.integer("a normal index", true), normal_count, "normal");
      }
    }
    const char next = in.peek();
    if (next != ' ' && next != '\t' && next != '\r' && next != '\n' && next != '#' && next != '\0')
      in.fail(fmt::format("expected a face corner v, v/vt, v//vn or v/vt/vn, got '{}'", in.preview()));
    uv_refs.add(corner, uv);
    normal_refs.add(corner, normal);
  }
  if (mesh.face_vertices.size() - first < 3)
    in.fail(fmt::format("a face needs at least 3 vertices, got {}", mesh.face_vertices.size() - first));
  if (mesh.face_vertices.size() > UINT32_MAX) in.fail("too many face corners");
  mesh.face_offsets.push_back(uint32_t(mesh.face_vertices.size()));
}

/// OpenSubdiv's tag line `t name ni/nf/ns ints... floats... strings...`; crease and corner are kept.
void parse_tag(TextCursor& in, PolyMesh& mesh) {
  const std::string name(in.token());
  std::array<long long, 3> counts{};
  for (size_t i = 0; i < 3; ++i) {
    counts[i] = in.integer("a tag argument count (ints/floats/strings)", i > 0);
    if (counts[i] < 0 || counts[i] > 1 << 20) in.fail(fmt::format("tag argument count {} is out of range", counts[i]));
    if (i < 2) {
      if (in.peek() != '/') in.fail("expected tag argument counts as ints/floats/strings");
      in.advance();
    }
  }
  std::vector<uint32_t> vertices;
  for (long long i = 0; i < counts[0]; ++i) {
    const long long v = in.integer("a vertex index (0-based) in the tag");
    if (v < 0 || size_t(v) >= mesh.positions.size())
      in.fail(fmt::format("tag vertex index {} is out of range (0..{})", v, long(mesh.positions.size()) - 1));
    vertices.push_back(uint32_t(v));
  }
  std::vector<float> sharpness;
  for (long long i = 0; i < counts[1]; ++i) {
    const double s = in.number("a tag sharpness");
    if (s < 0) in.fail(fmt::format("sharpness must be >= 0, got {}", s));
    sharpness.push_back(float(s));
  }
  for (long long i = 0; i < counts[2]; ++i)
    if (in.token().empty()) in.fail("expected a tag string argument");
  const auto sharp = [&](size_t i) { return sharpness.size() == 1 ? sharpness[0] : sharpness[i]; };
  if (name == "crease") {
    if (vertices.size() < 2 || (sharpness.size() != 1 && sharpness.size() != vertices.size() - 1))
      in.fail("expected 't crease 2/1/0 v0 v1 sharpness' (a chain of n vertices takes 1 or n-1 sharpnesses)");
    for (size_t i = 0; i + 1 < vertices.size(); ++i) mesh.creases.push_back({vertices[i], vertices[i + 1], sharp(i)});
  } else if (name == "corner") {
    if (vertices.empty() || (sharpness.size() != 1 && sharpness.size() != vertices.size()))
      in.fail("expected 't corner 1/1/0 v sharpness' (n vertices take 1 or n sharpnesses)");
    for (size_t i = 0; i < vertices.size(); ++i) mesh.corners.push_back({vertices[i], sharp(i)});
  }
}

/// Turns corner references into per-vertex values when every vertex always references the same item, into
/// face-varying values otherwise; drops them when some corners have none.
template <class T>
void resolve_refs(const CornerRefs& refs, const std::vector<T>& items, const PolyMesh& mesh, std::vector<T>& per_vertex,
                  std::vector<T>& per_corner) {
  if (!refs.any) return;
  if (std::find(refs.refs.begin(), refs.refs.end(), -1) != refs.refs.end()) return;
  std::vector<int32_t> at_vertex(mesh.vertex_count(), -1);
  bool consistent = true;
  for (size_t c = 0; c < refs.refs.size() && consistent; ++c) {
    int32_t& r = at_vertex[mesh.face_vertices[c]];
    if (r == -1) r = refs.refs[c];
    consistent = r == refs.refs[c];
  }
  if (consistent) {
    per_vertex.resize(mesh.vertex_count(), T(0.0));
    for (size_t v = 0; v < at_vertex.size(); ++v)
      if (at_vertex[v] >= 0) per_vertex[v] = items[size_t(at_vertex[v])];
    return;
  }
  per_corner.resize(refs.refs.size());
  for (size_t c = 0; c < refs.refs.size(); ++c) per_corner[c] = items[size_t(refs.refs[c])];
}

/// The bit patterns of a uv or normal, for writing each distinct value once.
using BitKey = std::array<uint64_t, 3>;
using detail::BitKeyHash;

}  // namespace

PolyMesh read_obj(std::string_view data, const std::string& name, Progress* progress) {
  TextCursor in(data, name, true);
  mesh_io::ByteProgress bytes(progress, data);
  in.set_progress(&bytes);
  PolyMesh mesh;
  std::vector<Vec2> uvs;
  std::vector<Vec3> normals;
  CornerRefs uv_refs, normal_refs;
  // One quick pass counting the statements saves the reallocation copies of growing arrays (a third of the time).
  const LineCounts counts = count_lines(data);
  mesh.positions.reserve(counts.v);
  uvs.reserve(counts.vt);
  normals.reserve(counts.vn);
  mesh.face_offsets.reserve(counts.f + 1);
  mesh.face_vertices.reserve(3 * counts.f);
  if (counts.vt > 0) uv_refs.refs.reserve(3 * counts.f);
  if (counts.vn > 0) normal_refs.refs.reserve(3 * counts.f);
  while (!in.at_end()) {
    if (in.at_line_end()) {
      in.next_line();
      continue;
    }
    const std::string_view key = in.token();
    if (key == "v") {
      Vec3 p;
      for (int i = 0; i < 3; ++i) p[i] = in.number("a vertex coordinate (v x y z)");
      std::array<double, 4> extra{};
      int n_extra = 0;
      while (n_extra < 4 && in.try_number(extra[size_t(n_extra)])) ++n_extra;
      if (n_extra == 3) {
        mesh.colors.resize(mesh.positions.size(), Vec3(1.0));
        mesh.colors.emplace_back(extra[0], extra[1], extra[2]);
      } else if (n_extra > 1) {
        in.fail("expected 'v x y z', 'v x y z w' or 'v x y z r g b'");
      }
      mesh.positions.push_back(p);
      in.end_line("a vertex");
    } else if (key == "vt") {
      Vec2 t;
      t.x = in.number("a texture coordinate (vt u v)");
      double v = 0, w;
      in.try_number(v);
      in.try_number(w);
      t.y = v;
      uvs.push_back(t);
      in.end_line("a texture coordinate");
    } else if (key == "vn") {
      Vec3 n;
      for (int i = 0; i < 3; ++i) n[i] = in.number("a normal component (vn x y z)");
      normals.push_back(n);
      in.end_line("a normal");
    } else if (key == "f") {
      parse_face(in, mesh, uvs.size(), normals.size(), uv_refs, normal_refs);
      in.next_line();
    } else if (key == "t") {
      parse_tag(in, mesh);
      in.end_line("a tag");
    } else if (is_ignored_statement(key)) {
      in.next_line();
    } else {
      in.fail(fmt::format("unknown OBJ statement '{}'", printable(key, 40)));
    }
  }
  if (!mesh.colors.empty()) mesh.colors.resize(mesh.positions.size(), Vec3(1.0));
  resolve_refs(uv_refs, uvs, mesh, mesh.uvs, mesh.corner_uvs);
  resolve_refs(normal_refs, normals, mesh, mesh.normals, mesh.corner_normals);
  bytes.finish();
  return mesh;
}

void write_obj(std::ostream& out, const PolyMesh& mesh) {
  BufferedWriter w(out);
  w.print("# written by tessera\n");
  for (size_t v = 0; v < mesh.vertex_count(); ++v) {
    const Vec3& p = mesh.positions[v];
    if (mesh.colors.size() == mesh.vertex_count())
      w.print("v {} {} {} {} {} {}\n", p.x, p.y, p.z, mesh.colors[v].x, mesh.colors[v].y, mesh.colors[v].z);
    else
      w.print("v {} {} {}\n", p.x, p.y, p.z);
  }
  // uvs and normals: face-varying ones one per corner (vt/vn index = corner + 1), per-vertex ones one per vertex.
  const bool corner_uv = mesh.corner_uvs.size() == mesh.face_vertices.size() && !mesh.corner_uvs.empty();
  const bool vertex_uv = !corner_uv && mesh.uvs.size() == mesh.vertex_count() && !mesh.uvs.empty();
  const bool corner_n = mesh.corner_normals.size() == mesh.face_vertices.size() && !mesh.corner_normals.empty();
  const bool vertex_n = !corner_n && mesh.normals.size() == mesh.vertex_count() && !mesh.normals.empty();
  // Per-corner values are written once each (a seam's corners share few distinct values): corner -> 1-based index.
  const auto write_distinct = [&](const auto& values, auto&& print) {
    std::vector<uint32_t> index(values.size());
    std::unordered_map<BitKey, uint32_t, BitKeyHash> seen;
    for (size_t c = 0; c < values.size(); ++c) {
      BitKey key{};
      for (int i = 0; i < values[c].length(); ++i) key[size_t(i)] = std::bit_cast<uint64_t>(values[c][i]);
      const auto [it, inserted] = seen.try_emplace(key, uint32_t(seen.size() + 1));
      if (inserted) print(values[c]);
      index[c] = it->second;
    }
    return index;
  };
  std::vector<uint32_t> uv_index, normal_index;
  const auto print_uv = [&](const Vec2& t) { w.print("vt {} {}\n", t.x, t.y); };
  const auto print_normal = [&](const Vec3& n) { w.print("vn {} {} {}\n", n.x, n.y, n.z); };
  if (corner_uv) uv_index = write_distinct(mesh.corner_uvs, print_uv);
  if (vertex_uv) std::for_each(mesh.uvs.begin(), mesh.uvs.end(), print_uv);
  if (corner_n) normal_index = write_distinct(mesh.corner_normals, print_normal);
  if (vertex_n) std::for_each(mesh.normals.begin(), mesh.normals.end(), print_normal);
  for (size_t f = 0; f < mesh.face_count(); ++f) {
    w.print("f");
    for (uint32_t c = mesh.face_offsets[f]; c < mesh.face_offsets[f + 1]; ++c) {
      const uint32_t v = mesh.face_vertices[c] + 1;
      const uint32_t t = corner_uv ? uv_index[c] : v, n = corner_n ? normal_index[c] : v;
      if ((corner_uv || vertex_uv) && (corner_n || vertex_n))
        w.print(" {}/{}/{}", v, t, n);
      else if (corner_uv || vertex_uv)
        w.print(" {}/{}", v, t);
      else if (corner_n || vertex_n)
        w.print(" {}//{}", v, n);
      else
        w.print(" {}", v);
    }
    w.print("\n");
  }
  for (const EdgeCrease& c : mesh.creases) w.print("t crease 2/1/0 {} {} {}\n", c.v0, c.v1, c.sharpness);
  for (const VertexCorner& c : mesh.corners) w.print("t corner 1/1/0 {} {}\n", c.v, c.sharpness);
}

}  // namespace tessera
