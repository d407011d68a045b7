// PLY reader and writer (Turk's format: a text header of elements and typed properties, then the rows of every
// element in ASCII or binary little/big endian).
#include <array>
#include <limits>
#include <optional>
#include <ostream>

#include "io_common.hpp"
#include "tessera/mesh/mesh_io.hpp"

namespace tessera {
namespace {

using mesh_io::fail_at_byte;
using mesh_io::fail_at_line;
using mesh_io::TextCursor;

enum class PlyType : uint8_t { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

constexpr std::array<size_t, 8> kTypeSize{1, 1, 2, 2, 4, 4, 4, 8};
/// The largest value of each integer type (colors stored as integers are scaled by it); 1 for floats.
constexpr std::array<double, 8> kTypeMax{127, 255, 32767, 65535, 2147483647.0, 4294967295.0, 1, 1};

size_t type_size(PlyType t) { return kTypeSize[size_t(t)]; }
bool is_float(PlyType t) { return t == PlyType::float32 || t == PlyType::float64; }

std::optional<PlyType> parse_type(std::string_view s) {
  static constexpr std::array<std::pair<std::string_view, PlyType>, 16> kNames{{
      {"char", PlyType::int8},
      {"int8", PlyType::int8},
      {"uchar", PlyType::uint8},
      {"uint8", PlyType::uint8},
      {"short", PlyType::int16},
      {"int16", PlyType::int16},
      {"ushort", PlyType::uint16},
      {"uint16", PlyType::uint16},
      {"int", PlyType::int32},
      {"int32", PlyType::int32},
      {"uint", PlyType::uint32},
      {"uint32", PlyType::uint32},
      {"float", PlyType::float32},
      {"float32", PlyType::float32},
      {"double", PlyType::float64},
      {"float64", PlyType::float64},
  }};
  for (const auto& [name, type] : kNames)
    if (name == s) return type;
  return std::nullopt;
}

/// Where a vertex property goes: position, normal, uv or color component, or nowhere.
enum Slot : int8_t { kSkip = -1, kX, kY, kZ, kNx, kNy, kNz, kU, kV, kRed, kGreen, kBlue, kSlotCount };

Slot vertex_slot(std::string_view name) {
  static constexpr std::array<std::pair<std::string_view, Slot>, 17> kNames{{
      {"x", kX},
      {"y", kY},
      {"z", kZ},
      {"nx", kNx},
      {"ny", kNy},
      {"nz", kNz},
      {"u", kU},
      {"v", kV},
      {"s", kU},
      {"t", kV},
      {"texture_u", kU},
      {"texture_v", kV},
      {"red", kRed},
      {"green", kGreen},
      {"blue", kBlue},
      {"diffuse_red", kRed},
      {"diffuse_green", kGreen},
  }};
  for (const auto& [n, slot] : kNames)
    if (n == name) return slot;
  return name == "diffuse_blue" ? kBlue : kSkip;
}

struct PlyProperty {
  std::string name;
  PlyType type;
  bool is_list = false;
  PlyType count_type = PlyType::uint8;
  Slot slot = kSkip;
  bool face_indices = false;
};

struct PlyElement {
  std::string name;
  uint64_t count = 0;
  std::vector<PlyProperty> properties;
  long line = 0;
  /// The fewest bytes a row can take: binary, lists empty; ASCII, one digit and one separator per value.
  size_t min_row_bytes(bool binary) const {
    size_t n = 0;
    for (const PlyProperty& p : properties) n += binary ? type_size(p.is_list ? p.count_type : p.type) : 2;
    return std::max<size_t>(n, 1);
  }
};

enum class Encoding { ascii, binary_little, binary_big };

struct PlyHeader {
  Encoding encoding = Encoding::ascii;
  std::vector<PlyElement> elements;
  const char* body = nullptr;
  long body_line = 0;
};

PlyHeader parse_header(std::string_view data, const std::string& name) {
  TextCursor in(data, name, false);
  if (in.token() != "ply") in.fail("expected 'ply' as the first line");
  in.end_line("'ply'");
  PlyHeader header;
  bool have_format = false;
  while (true) {
    if (in.at_end()) in.fail("expected 'end_header' before the end of the file");
    const std::string_view key = in.token();
    if (key.empty() || key == "comment" || key == "obj_info") {
      in.next_line();
      continue;
    }
    if (key == "end_header") {
      in.end_line("end_header");
      break;
    }
    if (key == "format") {
      const std::string_view enc = in.token();
      if (enc == "ascii")
        header.encoding = Encoding::ascii;
      else if (enc == "binary_little_endian")
        header.encoding = Encoding::binary_little;
      else if (enc == "binary_big_endian")
        header.encoding = Encoding::binary_big;
      else
        in.fail(fmt::format("expected ascii, binary_little_endian or binary_big_endian, got '{}'", enc));
      if (in.token() != "1.0") in.fail("expected format version 1.0");
      have_format = true;
    } else if (key == "element") {
      PlyElement e;
      e.name = std::string(in.token());
      if (e.name.empty()) in.fail("expected 'element <name> <count>'");
      const long long count = in.integer("an element count");
      if (count < 0) in.fail(fmt::format("element count {} is negative", count));
      e.count = uint64_t(count);
      e.line = in.line();
      for (const PlyElement& other : header.elements)
        if (other.name == e.name) in.fail(fmt::format("element '{}' is declared twice", e.name));
      header.elements.push_back(std::move(e));
    } else if (key == "property") {
      if (header.elements.empty()) in.fail("'property' before any 'element'");
      PlyElement& e = header.elements.back();
      PlyProperty p;
      std::string_view type = in.token();
      if (type == "list") {
        p.is_list = true;
        const auto count_type = parse_type(in.token());
        if (!count_type || is_float(*count_type)) in.fail("expected an integer list count type");
        p.count_type = *count_type;
        type = in.token();
      }
      const auto t = parse_type(type);
      if (!t) in.fail(fmt::format("unknown property type '{}'", type));
      p.type = *t;
      p.name = std::string(in.token());
      if (p.name.empty()) in.fail("expected a property name");
      if (e.name == "vertex" && !p.is_list) p.slot = vertex_slot(p.name);
      if (e.name == "face" && p.is_list && (p.name == "vertex_indices" || p.name == "vertex_index")) {
        if (is_float(p.type)) in.fail("face vertex indices must have an integer type");
        p.face_indices = true;
      }
      e.properties.push_back(std::move(p));
    } else {
      in.fail(fmt::format("unknown PLY header line '{}'", printable(key, 40)));
    }
    in.end_line("a header line");
  }
  if (!have_format) fail_at_byte(name, 0, "the PLY header has no 'format' line");
  for (const PlyElement& e : header.elements) {
    if (e.name == "vertex") {
      std::array<bool, 3> xyz{};
      for (const PlyProperty& p : e.properties)
        if (p.slot >= kX && p.slot <= kZ) xyz[size_t(p.slot)] = true;
      if (!(xyz[0] && xyz[1] && xyz[2])) fail_at_line(name, e.line, "the vertex element needs properties x, y and z");
    }
    if (e.name == "face" &&
        std::none_of(e.properties.begin(), e.properties.end(), [](const PlyProperty& p) { return p.face_indices; }))
      fail_at_line(name, e.line, "the face element needs a list property vertex_indices");
  }
  header.body = in.position();
  header.body_line = in.line();
  return header;
}

/// Values from a binary body.
class BinarySource {
 public:
  BinarySource(std::string_view data, const char* body, bool big_endian, const std::string& name,
               mesh_io::ByteProgress& bytes)
      : begin_(data.data()), p_(body), end_(data.data() + data.size()), big_(big_endian), name_(name), bytes_(bytes) {}

  double value(PlyType t, const char* what) {
    const size_t n = type_size(t);
    if (size_t(end_ - p_) < n) fail(fmt::format("expected {}, but the file ends", what));
    double v = 0;
    switch (t) {
      case PlyType::int8:
        v = double(int8_t(*p_));
        break;
      case PlyType::uint8:
        v = double(uint8_t(*p_));
        break;
      case PlyType::int16:
        v = mesh_io::load_scalar<int16_t>(p_, big_);
        break;
      case PlyType::uint16:
        v = mesh_io::load_scalar<uint16_t>(p_, big_);
        break;
      case PlyType::int32:
        v = mesh_io::load_scalar<int32_t>(p_, big_);
        break;
      case PlyType::uint32:
        v = mesh_io::load_scalar<uint32_t>(p_, big_);
        break;
      case PlyType::float32:
        v = mesh_io::load_scalar<float>(p_, big_);
        break;
      case PlyType::float64:
        v = mesh_io::load_scalar<double>(p_, big_);
        break;
    }
    if (!std::isfinite(v)) fail(fmt::format("expected {}, got a non-finite number", what));
    p_ += n;
    return v;
  }
  void end_row() { bytes_.at(p_); }
  size_t remaining() const { return size_t(end_ - p_); }
  [[noreturn]] void fail(const std::string& what) const { fail_at_byte(name_, p_ - begin_, what); }
  /// The bytes one list item takes at least.
  static size_t min_item_bytes(PlyType t) { return type_size(t); }

 private:
  const char* begin_;
  const char* p_;
  const char* end_;
  bool big_;
  const std::string& name_;
  mesh_io::ByteProgress& bytes_;
};

/// Values from an ASCII body: one row per line.
class AsciiSource {
 public:
  AsciiSource(std::string_view body, long first_line, const std::string& name, mesh_io::ByteProgress& bytes)
      : in_(body, name, false, first_line) {
    in_.set_progress(&bytes);
    in_.skip_empty_lines();
  }

  double value(PlyType t, const char* what) {
    double v;
    if (!in_.try_number(v)) fail(fmt::format("expected {}, got '{}'", what, in_.preview()));
    if (!is_float(t) && v != std::floor(v)) fail(fmt::format("expected an integer for {}, got {}", what, v));
    // A float property holds a float: the decimal text (shortest digits of a float) reads back as that float.
    return t == PlyType::float32 ? double(float(v)) : v;
  }
  void end_row() {
    if (!in_.at_line_end()) fail(fmt::format("expected the end of the row, got '{}'", in_.preview()));
    in_.next_line();
    in_.skip_empty_lines();
  }
  size_t remaining() const { return in_.remaining(); }
  [[noreturn]] void fail(const std::string& what) const { in_.fail(what); }
  static size_t min_item_bytes(PlyType) { return 2; }

 private:
  TextCursor in_;
};

template <class Source>
void read_body(Source& src, const std::vector<PlyElement>& elements, bool binary, PolyMesh& mesh) {
  bool vertices_read = false;
  std::array<bool, kSlotCount> present{};
  std::array<double, kSlotCount> row{};
  for (const PlyElement& e : elements) {
    if (e.count > src.remaining() / e.min_row_bytes(binary))
      src.fail(fmt::format("element '{}' declares {} rows, more than the remaining {} bytes can hold", e.name, e.count,
                           src.remaining()));
    if (e.count > UINT32_MAX) src.fail(fmt::format("element '{}' has too many rows ({})", e.name, e.count));
    const bool is_vertex = e.name == "vertex", is_face = e.name == "face";
    if (is_vertex) {
      for (const PlyProperty& p : e.properties)
        if (p.slot != kSkip) present[size_t(p.slot)] = true;
      mesh.positions.reserve(e.count);
      if (present[kNx] && present[kNy] && present[kNz]) mesh.normals.reserve(e.count);
      if (present[kU] && present[kV]) mesh.uvs.reserve(e.count);
      if (present[kRed] && present[kGreen] && present[kBlue]) mesh.colors.reserve(e.count);
    }
    if (is_face) mesh.face_offsets.reserve(e.count + 1);
    for (uint64_t r = 0; r < e.count; ++r) {
      for (const PlyProperty& p : e.properties) {
        if (!p.is_list) {
          const double v = src.value(p.type, "a property value");
          if (p.slot != kSkip) row[size_t(p.slot)] = p.slot >= kRed ? v / kTypeMax[size_t(p.type)] : v;
          continue;
        }
        const double count = src.value(p.count_type, "a list count");
        if (count < 0 || count > double(src.remaining() / Source::min_item_bytes(p.type)))
          src.fail(fmt::format("list count {} is negative or larger than the rest of the file", count));
        if (p.face_indices && count < 3) src.fail(fmt::format("a face needs at least 3 vertices, got {}", count));
        for (size_t i = 0; i < size_t(count); ++i) {
          const double index = src.value(p.type, "a vertex index");
          if (!p.face_indices) continue;
          if (index < 0 || index > double(UINT32_MAX) || (vertices_read && index >= double(mesh.positions.size())))
            src.fail(fmt::format("vertex index {} is out of range (0..{})", index, long(mesh.positions.size()) - 1));
          mesh.face_vertices.push_back(uint32_t(index));
        }
        if (p.face_indices) mesh.face_offsets.push_back(uint32_t(mesh.face_vertices.size()));
      }
      src.end_row();
      if (!is_vertex) continue;
      mesh.positions.emplace_back(row[kX], row[kY], row[kZ]);
      if (present[kNx] && present[kNy] && present[kNz]) mesh.normals.emplace_back(row[kNx], row[kNy], row[kNz]);
      if (present[kU] && present[kV]) mesh.uvs.emplace_back(row[kU], row[kV]);
      if (present[kRed] && present[kGreen] && present[kBlue])
        mesh.colors.emplace_back(row[kRed], row[kGreen], row[kBlue]);
    }
    if (is_vertex) vertices_read = true;
  }
}

}  // namespace

PolyMesh read_ply(std::string_view data, const std::string& name, Progress* progress) {
  const PlyHeader header = parse_header(data, name);
  PolyMesh mesh;
  mesh_io::ByteProgress bytes(progress, data);
  const std::string_view body(header.body, size_t(data.data() + data.size() - header.body));
  if (header.encoding == Encoding::ascii) {
    AsciiSource src(body, header.body_line, name, bytes);
    read_body(src, header.elements, false, mesh);
  } else {
    BinarySource src(data, header.body, header.encoding == Encoding::binary_big, name, bytes);
    read_body(src, header.elements, true, mesh);
  }
  // Faces listed before their vertices are checked now that the vertex count is known.
  for (uint32_t v : mesh.face_vertices)
    if (v >= mesh.positions.size())
      throw InvalidInput(
          located(name, fmt::format("vertex index {} is out of range (0..{})", v, long(mesh.positions.size()) - 1)));
  bytes.finish();
  return mesh;
}

void write_ply(std::ostream& out, const PolyMesh& mesh, const MeshWriteOptions& options) {
  const bool binary = options.binary;
  const size_t nv = mesh.vertex_count();
  const bool normals = !mesh.normals.empty() && mesh.normals.size() == nv;
  const bool uvs = !mesh.uvs.empty() && mesh.uvs.size() == nv;
  const bool colors = !mesh.colors.empty() && mesh.colors.size() == nv;
  uint32_t largest_face = 0;
  for (size_t f = 0; f < mesh.face_count(); ++f) largest_face = std::max(largest_face, mesh.face_size(f));
  const bool wide_count = largest_face > 255;

  std::string head = fmt::format("ply\nformat {} 1.0\ncomment written by tessera\nelement vertex {}\n",
                                 binary ? "binary_little_endian" : "ascii", nv);
  const char* real = options.double_precision ? "double" : "float";
  for (const char* axis : {"x", "y", "z"}) head += fmt::format("property {} {}\n", real, axis);
  if (normals)
    for (const char* axis : {"nx", "ny", "nz"}) head += fmt::format("property {} {}\n", real, axis);
  if (uvs)
    for (const char* axis : {"s", "t"}) head += fmt::format("property {} {}\n", real, axis);
  if (colors) head += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  head += fmt::format("element face {}\nproperty list {} int vertex_indices\nend_header\n", mesh.face_count(),
                      wide_count ? "int" : "uchar");
  out.write(head.data(), std::streamsize(head.size()));

  const auto color_byte = [](double c) { return uint8_t(std::lround(std::clamp(c, 0.0, 1.0) * 255.0)); };
  // Text keeps the shortest digits that read back as the stored type; binary stores that type.
  const auto print_reals = [&](mesh_io::BufferedWriter& w, std::initializer_list<double> values) {
    for (double x : values) {
      if (options.double_precision)
        w.print(" {}", x);
      else
        w.print(" {}", float(x));
    }
  };
  const auto store_real = [&](std::string& bytes, double x) {
    if (options.double_precision)
      mesh_io::store_le(bytes, x);
    else
      mesh_io::store_le(bytes, float(x));
  };
  if (!binary) {
    mesh_io::BufferedWriter w(out);
    for (size_t v = 0; v < nv; ++v) {
      const Vec3& p = mesh.positions[v];
      if (options.double_precision)
        w.print("{}", p.x);
      else
        w.print("{}", float(p.x));
      print_reals(w, {p.y, p.z});
      if (normals) print_reals(w, {mesh.normals[v].x, mesh.normals[v].y, mesh.normals[v].z});
      if (uvs) print_reals(w, {mesh.uvs[v].x, mesh.uvs[v].y});
      if (colors)
        w.print(" {} {} {}", color_byte(mesh.colors[v].x), color_byte(mesh.colors[v].y), color_byte(mesh.colors[v].z));
      w.print("\n");
    }
    for (size_t f = 0; f < mesh.face_count(); ++f) {
      w.print("{}", mesh.face_size(f));
      for (uint32_t v : mesh.face(f)) w.print(" {}", v);
      w.print("\n");
    }
    return;
  }
  std::string body;
  for (size_t v = 0; v < nv; ++v) {
    for (int i = 0; i < 3; ++i) store_real(body, mesh.positions[v][i]);
    if (normals)
      for (int i = 0; i < 3; ++i) store_real(body, mesh.normals[v][i]);
    if (uvs)
      for (int i = 0; i < 2; ++i) store_real(body, mesh.uvs[v][i]);
    if (colors)
      for (int i = 0; i < 3; ++i) mesh_io::store_le(body, color_byte(mesh.colors[v][i]));
    if (body.size() > (1 << 20)) {
      out.write(body.data(), std::streamsize(body.size()));
      body.clear();
    }
  }
  for (size_t f = 0; f < mesh.face_count(); ++f) {
    if (wide_count)
      mesh_io::store_le(body, int32_t(mesh.face_size(f)));
    else
      mesh_io::store_le(body, uint8_t(mesh.face_size(f)));
    for (uint32_t v : mesh.face(f)) mesh_io::store_le(body, int32_t(v));
    if (body.size() > (1 << 20)) {
      out.write(body.data(), std::streamsize(body.size()));
      body.clear();
    }
  }
  out.write(body.data(), std::streamsize(body.size()));
}

}  // namespace tessera
