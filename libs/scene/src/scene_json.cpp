// The JSON scene loader (docs/scene-format.md): every value is checked where it is read, and errors name the JSON
// path of the bad value.
#include "scene_json.hpp"

#include <algorithm>
#include <nlohmann/json.hpp>
#include <set>

#include "tessera/core/atomic_file.hpp"
#include "tessera/core/error.hpp"
#include "tessera/core/parse.hpp"
#include "tessera/glsl/program.hpp"
#include "tessera/image/image_io.hpp"
#include "tessera/image/texture.hpp"
#include "tessera/math/transform.hpp"
#include "tessera/mesh/convert.hpp"
#include "tessera/mesh/mesh_io.hpp"
#include "tessera/mesh/normals.hpp"
#include "tessera/mesh/primitives.hpp"
#include "tessera/raytrace/render.hpp"
#include "tessera/scene/scene.hpp"

namespace tessera {
namespace {

using detail::Json;

/// nlohmann's DOM parser, also remembering the byte where parsing failed (a parse_error carries its byte, but a number
/// out of range ("1e999") is reported as an out_of_range exception without one) and refusing duplicate keys (the DOM
/// would silently keep the last one, so `"radius": 1, ..., "radius": 2` would ignore a value the user wrote).
/// sax_parse calls the members below on this type, so they hide the base's: each tracks the path of the value it
/// sees ("objects[3].material"), then forwards.
struct LocatingParser : nlohmann::detail::json_sax_dom_parser<Json> {
  using Base = nlohmann::detail::json_sax_dom_parser<Json>;
  LocatingParser(Json& doc, std::string name) : Base(doc), name_(std::move(name)) {}
  size_t error_byte = 0;
  template <class Exception>
  bool parse_error(size_t byte, const std::string& token, const Exception& e) {
    error_byte = byte;
    return Base::parse_error(byte, token, e);
  }
  bool start_object(size_t n) {
    enter(false);
    return Base::start_object(n);
  }
  bool start_array(size_t n) {
    enter(true);
    return Base::start_array(n);
  }
  bool end_object() {
    frames_.pop_back();
    return Base::end_object();
  }
  bool end_array() {
    frames_.pop_back();
    return Base::end_array();
  }
  bool key(string_t& k) {
    Frame& f = frames_.back();
    if (!f.keys.insert(k).second)
      throw InvalidInput(located(name_, fmt::format("{}: duplicate key '{}' (each key may appear once in an object)",
                                                    f.path.empty() ? "(top level)" : f.path, printable(k))));
    f.last_key = k;
    return Base::key(k);
  }
  bool null() { return scalar(), Base::null(); }
  bool boolean(bool v) { return scalar(), Base::boolean(v); }
  bool number_integer(number_integer_t v) { return scalar(), Base::number_integer(v); }
  bool number_unsigned(number_unsigned_t v) { return scalar(), Base::number_unsigned(v); }
  bool number_float(number_float_t v, const string_t& s) { return scalar(), Base::number_float(v, s); }
  bool string(string_t& v) { return scalar(), Base::string(v); }

 private:
  struct Frame {
    std::string path;
    bool array;
    size_t count = 0;
    std::set<std::string> keys;
    std::string last_key;
  };
  /// Opens an object or array, refusing nesting deeper than kMaxDepth: the format needs a few levels, and a million
  /// '[' would cost the paths' memory (each level keeps its own) and the recursion of whatever walks the document.
  void enter(bool array) {
    if (frames_.size() >= kMaxDepth)
      throw InvalidInput(located(name_, fmt::format("{}: objects and arrays nested deeper than {} levels",
                                                    printable(frames_.back().path), kMaxDepth)));
    frames_.push_back({child_path(), array});
  }
  static constexpr size_t kMaxDepth = 64;
  /// The path of the value that starts now; counts it when it is an array element.
  std::string child_path() {
    if (frames_.empty()) return "";
    Frame& f = frames_.back();
    if (f.array) return fmt::format("{}[{}]", f.path, f.count++);
    return f.path.empty() ? f.last_key : f.path + "." + f.last_key;
  }
  void scalar() {
    if (!frames_.empty() && frames_.back().array) ++frames_.back().count;
  }
  std::string name_;
  std::vector<Frame> frames_;
};

/// A JSON value and its path in the document ("objects[3].radius"), with typed, checked accessors.
class Node {
 public:
  Node(const Json& value, std::string path, const std::string& file) : v_(value), path_(std::move(path)), file_(file) {}

  [[noreturn]] void fail(const std::string& what) const {
    throw InvalidInput(located(file_, (path_.empty() ? std::string("(top level)") : path_) + ": " + what));
  }
  const std::string& path() const { return path_; }
  const Json& json() const { return v_; }

  bool has(const char* key) const { return v_.contains(key); }
  Node operator[](const char* key) const {
    if (!has(key)) Node(v_, join(key), file_).fail("missing");
    return Node(v_.at(key), join(key), file_);
  }
  Node item(size_t i) const { return Node(v_.at(i), fmt::format("{}[{}]", path_, i), file_); }
  size_t size() const { return v_.size(); }

  /// Fails on a key that is not in `allowed` (a misspelt key would otherwise be silently ignored).
  void expect_object() const {
    if (!v_.is_object()) fail("expected an object");
  }
  void only(std::initializer_list<const char*> allowed) const {
    expect_object();
    const std::set<std::string> keys(allowed.begin(), allowed.end());
    for (const auto& [key, value] : v_.items())
      if (!keys.count(key)) Node(value, join(key.c_str()), file_).fail("unknown key");
  }
  void expect_array(size_t min_size = 0) const {
    if (!v_.is_array()) fail("expected an array");
    if (v_.size() < min_size) fail(fmt::format("expected at least {} elements", min_size));
  }

  double number() const {
    if (!v_.is_number()) fail("expected a number");
    const double d = v_.get<double>();
    if (!std::isfinite(d)) fail("expected a finite number");
    return d;
  }
  double positive() const {
    if (!v_.is_number() || !(v_.get<double>() > 0) || !std::isfinite(v_.get<double>()))
      fail("expected a positive number");
    return v_.get<double>();
  }
  double non_negative() const {
    if (!v_.is_number() || !(v_.get<double>() >= 0) || !std::isfinite(v_.get<double>()))
      fail("expected a non-negative number");
    return v_.get<double>();
  }
  /// An integer, also written as a number with no fraction (4.0: what a keyed value gives at a key).
  int integer(int lo, int hi) const {
    const double d = v_.is_number() ? v_.get<double>() : std::nan("");
    if (!(d >= lo && d <= hi && d == std::floor(d))) fail(fmt::format("expected an integer in [{}, {}]", lo, hi));
    return int(d);
  }
  bool boolean() const {
    if (!v_.is_boolean()) fail("expected true or false");
    return v_.get<bool>();
  }
  std::string string() const {
    if (!v_.is_string()) fail("expected a string");
    return v_.get<std::string>();
  }
  Vec3 vec3() const {
    if (!v_.is_array() || v_.size() != 3) fail("expected an array of 3 numbers");
    return {item(0).number(), item(1).number(), item(2).number()};
  }
  /// A color: [r, g, b] or one number for a gray; components non-negative.
  Vec3f color() const {
    if (v_.is_number()) return Vec3f(float(non_negative()));
    if (!v_.is_array() || v_.size() != 3) fail("expected a color: [r, g, b] or a number");
    return Vec3f(float(item(0).non_negative()), float(item(1).non_negative()), float(item(2).non_negative()));
  }

 private:
  std::string join(const char* key) const { return path_.empty() ? std::string(key) : path_ + "." + key; }

  const Json& v_;
  std::string path_;
  const std::string& file_;
};

Vec3f vec3f(const Node& n) { return Vec3f(n.vec3()); }

void read_image_settings(const Node& n, SceneImage& image) {
  n.only({"size", "samples", "depth", "background"});
  if (n.has("size")) {
    const Node size = n["size"];
    if (!size.json().is_array() || size.size() != 2) size.fail("expected [width, height]");
    image.width = size.item(0).integer(1, 65536);
    image.height = size.item(1).integer(1, 65536);
  }
  if (n.has("samples")) image.samples = n["samples"].integer(1, SceneImage::kMaxSamples);
  if (n.has("depth")) image.max_depth = n["depth"].integer(1, RenderSettings::kMaxDepth);
  if (n.has("background")) image.background = n["background"].color();
}

void read_camera(const Node& n, SceneCamera& c) {
  n.only({"eye", "center", "up", "fovy", "aperture", "focal_distance", "projection", "ortho_height"});
  if (n.has("eye")) c.eye = n["eye"].vec3();
  if (n.has("center")) c.center = n["center"].vec3();
  if (n.has("up")) c.up = n["up"].vec3();
  if (n.has("fovy")) {
    c.fovy = n["fovy"].positive();
    if (c.fovy >= 180) n["fovy"].fail("expected a number of degrees in (0, 180)");
  }
  if (n.has("aperture")) c.aperture = n["aperture"].non_negative();
  if (n.has("focal_distance")) c.focal_distance = n["focal_distance"].non_negative();
  if (glm::length(c.center - c.eye) == 0) n.fail("eye and center coincide");
  if (glm::length(glm::cross(c.up, c.center - c.eye)) == 0) n.fail("up is parallel to the view direction");
  if (n.has("projection")) {
    const std::string projection = n["projection"].string();
    if (projection != "perspective" && projection != "orthographic")
      n["projection"].fail("expected perspective or orthographic");
    c.orthographic = projection == "orthographic";
  }
  if (n.has("ortho_height")) {
    if (!c.orthographic) n["ortho_height"].fail("applies to \"projection\": \"orthographic\" only");
    c.ortho_height = n["ortho_height"].positive();
  } else {
    // What the perspective view frames at the center: switching the projection keeps the subject's size there.
    c.ortho_height = 2 * glm::length(c.center - c.eye) * std::tan(radians(c.fovy) / 2);
  }
}

Light read_light(const Node& n) {
  Light l;
  n.expect_object();  // before its type is read, so that [1] is not reported as a missing type
  const std::string type = n["type"].string();
  if (type == "point") {
    n.only({"type", "position", "color"});
    l.type = LightType::point;
    l.position = vec3f(n["position"]);
  } else if (type == "directional") {
    n.only({"type", "direction", "color"});
    l.type = LightType::directional;
    l.direction = vec3f(n["direction"]);
    if (glm::length(l.direction) == 0) n["direction"].fail("expected a nonzero vector");
  } else if (type == "rect") {
    n.only({"type", "corner", "edge_u", "edge_v", "color", "samples", "visible"});
    l.type = LightType::rect;
    l.position = vec3f(n["corner"]);
    l.edge_u = vec3f(n["edge_u"]);
    l.edge_v = vec3f(n["edge_v"]);
    if (glm::length(glm::cross(l.edge_u, l.edge_v)) == 0) n.fail("edge_u and edge_v must span a rectangle");
  } else if (type == "disk") {
    n.only({"type", "center", "normal", "radius", "color", "samples", "visible"});
    l.type = LightType::disk;
    l.position = vec3f(n["center"]);
    l.direction = vec3f(n["normal"]);
    if (glm::length(l.direction) == 0) n["normal"].fail("expected a nonzero vector");
    l.radius = float(n["radius"].positive());
  } else if (type == "sphere") {
    n.only({"type", "center", "radius", "color", "samples", "visible"});
    l.type = LightType::sphere;
    l.position = vec3f(n["center"]);
    l.radius = float(n["radius"].positive());
  } else {
    n["type"].fail("expected point, directional, rect, disk or sphere");
  }
  if (n.has("color")) l.color = n["color"].color();
  if (n.has("samples")) l.samples = n["samples"].integer(1, 4096);
  if (n.has("visible")) l.visible = n["visible"].boolean();
  return l;
}

float read_ior(const Node& n) {
  if (n.json().is_string()) {
    static const std::map<std::string, float> table = {{"vacuum", ior::kVacuum}, {"air", ior::kAir},
                                                       {"water", ior::kWater},   {"glass", ior::kGlass},
                                                       {"ice", ior::kIce},       {"diamond", ior::kDiamond}};
    const auto it = table.find(n.string());
    if (it == table.end()) n.fail("expected a number or one of air, water, glass, ice, diamond, vacuum");
    return it->second;
  }
  return float(n.positive());
}

/// A material's "shader": a GLSL program from the files "vertex" and "fragment" (relative to the scene), its
/// "uniforms" ({"name": number or [numbers]}) and "textures" ({"unit": "image"}).
std::shared_ptr<raster3d::ContextProgram> read_shader(const Node& n, const std::filesystem::path& base_dir) {
  n.only({"vertex", "fragment", "uniforms", "textures"});
  const auto source = [&](const char* key) {
    try {
      return glsl::read_shader((base_dir / n[key].string()).string());
    } catch (const IoError& e) {
      n[key].fail(e.what());
    }
  };
  std::shared_ptr<glsl::Program> program;
  try {
    program = std::make_shared<glsl::Program>(glsl::Program::compile(source("vertex"), source("fragment")));
  } catch (const glsl::CompileError& e) {
    n.fail(e.what());
  }
  if (n.has("uniforms")) {
    const Node uniforms = n["uniforms"];
    uniforms.expect_object();
    for (const auto& [name, value] : uniforms.json().items()) {
      const Node u = uniforms[name.c_str()];
      std::string text;
      if (u.json().is_array()) {
        u.expect_array(1);
        for (size_t i = 0; i < u.size(); ++i) text += (i ? "," : "") + fmt::format("{}", u.item(i).number());
      } else {
        text = fmt::format("{}", u.number());
      }
      try {
        program->set_uniform_text(name, text);
      } catch (const InvalidInput& e) {
        u.fail(e.what());
      }
    }
  }
  if (n.has("textures")) {
    const Node textures = n["textures"];
    textures.expect_object();
    for (const auto& [unit, value] : textures.json().items()) {
      const Node t = textures[unit.c_str()];
      if (unit.empty() || unit.size() > 2 || !std::all_of(unit.begin(), unit.end(), ::isdigit) || std::stoi(unit) > 15)
        t.fail("expected a texture unit 0 to 15 as the key");
      program->bind_texture(std::stoi(unit), std::make_shared<Texture2D>(load_texture(base_dir / t.string())));
    }
  }
  return program;
}

Material read_material(const Node& n, const std::filesystem::path& base_dir) {
  n.only({"diffuse", "ambient", "specular", "shininess", "model", "reflection", "transmission", "ior", "fresnel",
          "glossiness", "emission", "checker", "texture", "shader"});
  Material m;
  if (n.has("diffuse")) m.diffuse = n["diffuse"].color();
  if (n.has("ambient")) m.ambient = n["ambient"].color();
  if (n.has("specular")) m.specular = n["specular"].color();
  if (n.has("shininess")) m.shininess = float(n["shininess"].positive());
  if (n.has("model")) {
    const std::string model = n["model"].string();
    if (model != "phong" && model != "blinn") n["model"].fail("expected phong or blinn");
    m.model = model == "phong" ? SpecularModel::phong : SpecularModel::blinn;
  }
  if (n.has("reflection")) m.reflection = n["reflection"].color();
  if (n.has("transmission")) m.transmission = n["transmission"].color();
  if (n.has("ior")) m.ior = read_ior(n["ior"]);
  if (n.has("fresnel")) m.fresnel = n["fresnel"].boolean();
  if (n.has("glossiness")) {
    m.glossiness = float(n["glossiness"].non_negative());
    if (m.glossiness > 1) n["glossiness"].fail("expected a number in [0, 1]");
  }
  if (n.has("emission")) m.emission = n["emission"].color();
  if (n.has("checker")) {
    const Node c = n["checker"];
    c.only({"size", "color"});
    m.checker = float(c["size"].positive());
    m.checker_color = c["color"].color();
  }
  if (n.has("texture")) m.texture = std::make_shared<Texture2D>(load_texture(base_dir / n["texture"].string()));
  return m;
}

/// The transform list: each entry right-multiplies the matrix (M = T0 T1 ... Tn, so the last entry acts first, as
/// the notes' and OpenGL's transform calls).
Mat4 read_transform(const Node& n) {
  n.expect_array();
  Mat4 m(1.0);
  for (size_t i = 0; i < n.size(); ++i) {
    const Node step = n.item(i);
    if (!step.json().is_object() || step.json().size() != 1)
      step.fail(
          "expected one of {\"translate\": [x,y,z]}, {\"rotate\": {\"angle\": deg, \"axis\": [x,y,z]}}, "
          "{\"scale\": [x,y,z] or s}, {\"matrix\": [16 numbers, row by row]}");
    if (step.has("translate")) {
      const Vec3 t = step["translate"].vec3();
      m = m * translate(t.x, t.y, t.z);
    } else if (step.has("rotate")) {
      const Node r = step["rotate"];
      r.only({"angle", "axis"});
      const Vec3 axis = r["axis"].vec3();
      if (glm::length(axis) == 0) r["axis"].fail("expected a nonzero vector");
      m = m * rotate(radians(r["angle"].number()), axis);
    } else if (step.has("scale")) {
      const Node s = step["scale"];
      const Vec3 v = s.json().is_number() ? Vec3(s.number()) : s.vec3();
      if (v.x == 0 || v.y == 0 || v.z == 0) s.fail("expected nonzero scale factors");
      m = m * scale(v.x, v.y, v.z);
    } else if (step.has("matrix")) {
      const Node a = step["matrix"];
      if (!a.json().is_array() || a.size() != 16) a.fail("expected 16 numbers (row by row)");
      Mat4 t;
      for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) t[c][r] = a.item(size_t(r * 4 + c)).number();  // GLM is column-major
      if (std::abs(glm::determinant(t)) < 1e-12) a.fail("the matrix is singular");
      m = m * t;
    } else {
      step.fail("expected translate, rotate, scale or matrix");
    }
  }
  return m;
}

/// A generated mesh: {"primitive": "torus" | "sphere" | "cube" | "icosahedron" | ..., "segments": n, ...}.
PolyMesh generated_mesh(const Node& n) {
  const std::string kind = n["primitive"].string();
  const int segments = n.has("segments") ? n["segments"].integer(3, 4096) : 32;
  if (kind == "torus") {
    const double major = n.has("major_radius") ? n["major_radius"].positive() : 1.0;
    const double minor = n.has("minor_radius") ? n["minor_radius"].positive() : 0.3;
    if (minor >= major) n["minor_radius"].fail("expected a number below major_radius");
    return make_torus(major, minor, segments, std::max(3, segments / 2));
  }
  if (kind == "sphere") return make_uv_sphere(segments, std::max(2, segments / 2));
  if (kind == "cube") return make_box();
  if (kind == "cylinder") return make_cylinder(segments);
  if (kind == "cone") return make_cone(segments);
  if (kind == "tetrahedron") return make_tetrahedron();
  if (kind == "octahedron") return make_octahedron();
  if (kind == "dodecahedron") return make_dodecahedron();
  if (kind == "icosahedron") return make_icosahedron();
  n["primitive"].fail(
      "expected torus, sphere, cube, cylinder, cone, tetrahedron, octahedron, dodecahedron or "
      "icosahedron");
}

std::shared_ptr<const TriMesh> read_mesh_object(const Node& n, const std::filesystem::path& base_dir) {
  if (n.has("file") == n.has("primitive")) n.fail("a mesh needs exactly one of file and primitive");
  PolyMesh poly = n.has("file") ? read_mesh(base_dir / n["file"].string()) : generated_mesh(n);
  const bool smooth = n.has("smooth") ? n["smooth"].boolean() : true;
  if (smooth && poly.normals.empty()) compute_vertex_normals(poly);
  TriMesh tri = to_tri_mesh(poly);
  if (!smooth) tri.normals.clear();
  if (tri.triangle_count() == 0) n.fail("the mesh has no faces");
  return std::make_shared<const TriMesh>(std::move(tri));
}

Shape read_shape(const Node& n, const std::string& type) {
  const auto radius = [&] { return n.has("radius") ? float(n["radius"].positive()) : 1.0f; };
  const auto point = [&](const char* key, Vec3f fallback) { return n.has(key) ? vec3f(n[key]) : fallback; };
  const auto normal = [&] {
    const Vec3f v = point("normal", {0, 1, 0});
    if (glm::length(v) == 0) n["normal"].fail("expected a nonzero vector");
    return glm::normalize(v);
  };
  const auto vertices = [&](size_t min_count) {
    const Node vs = n["vertices"];
    vs.expect_array(min_count);
    std::vector<Vec3f> out;
    for (size_t i = 0; i < vs.size(); ++i) out.push_back(vec3f(vs.item(i)));
    // Newell's normal is twice the signed area vector: zero for collinear or coincident vertices.
    Vec3 area(0.0);
    for (size_t i = 0; i < out.size(); ++i) area += glm::cross(Vec3(out[i]), Vec3(out[(i + 1) % out.size()]));
    if (glm::length(area) < 1e-12) vs.fail("the vertices enclose no area");
    return out;
  };
  const auto capped = [&] { return n.has("capped") ? n["capped"].boolean() : true; };
  if (type == "sphere") return Sphere{point("center", Vec3f(0.0f)), radius()};
  if (type == "plane") return Plane{point("point", Vec3f(0.0f)), normal()};
  if (type == "triangle") {
    const auto v = vertices(3);
    if (v.size() != 3) n["vertices"].fail("expected 3 vertices");
    return Triangle{v[0], v[1], v[2]};
  }
  if (type == "polygon") {
    Polygon p{vertices(3)};
    if (n.has("test")) {
      const std::string t = n["test"].string();
      if (t == "crossing")
        p.test = PointInPolygon::crossing;
      else if (t == "winding")
        p.test = PointInPolygon::winding;
      else if (t == "half_plane")
        p.test = PointInPolygon::half_plane;
      else
        n["test"].fail("expected crossing, winding or half_plane");
    }
    return p;
  }
  if (type == "box") {
    const Vec3f lo = point("min", Vec3f(-1.0f)), hi = point("max", Vec3f(1.0f));
    if (!(lo.x < hi.x && lo.y < hi.y && lo.z < hi.z)) n.fail("expected min < max in every coordinate");
    return Box{lo, hi};
  }
  if (type == "cylinder") {
    Cylinder c{radius(), n.has("y0") ? float(n["y0"].number()) : 0.0f, n.has("y1") ? float(n["y1"].number()) : 1.0f,
               capped()};
    if (!(c.y0 < c.y1)) n.fail("expected y0 < y1");
    return c;
  }
  if (type == "cone")
    return Cone{point("apex", Vec3f(0.0f)), radius(), n.has("height") ? float(n["height"].positive()) : 1.0f, capped()};
  if (type == "disk") return Disk{point("center", Vec3f(0.0f)), normal(), radius()};
  if (type == "ellipsoid") {
    const Vec3f r = point("radii", Vec3f(1.0f));
    if (!(r.x > 0 && r.y > 0 && r.z > 0)) n["radii"].fail("expected three positive numbers");
    return Ellipsoid{point("center", Vec3f(0.0f)), r};
  }
  n["type"].fail("expected sphere, plane, triangle, polygon, box, cylinder, cone, disk, ellipsoid or mesh");
}

SceneObject read_object(const Node& n, const Scene& scene, const std::filesystem::path& base_dir) {
  n.expect_object();  // before its type is read, so that [1] is not reported as a missing type
  const std::string type = n["type"].string();
  static const std::map<std::string, std::vector<const char*>> shape_keys = {
      {"sphere", {"center", "radius"}},
      {"plane", {"point", "normal"}},
      {"triangle", {"vertices"}},
      {"polygon", {"vertices", "test"}},
      {"box", {"min", "max"}},
      {"cylinder", {"radius", "y0", "y1", "capped"}},
      {"cone", {"apex", "radius", "height", "capped"}},
      {"disk", {"center", "normal", "radius"}},
      {"ellipsoid", {"center", "radii"}},
      {"mesh", {"file", "primitive", "segments", "major_radius", "minor_radius", "smooth"}}};
  const auto keys = shape_keys.find(type);
  if (keys == shape_keys.end())
    n["type"].fail("expected sphere, plane, triangle, polygon, box, cylinder, cone, disk, ellipsoid or mesh");
  std::set<std::string> allowed = {"type", "material", "transform", "transform_end", "velocity", "casts_shadows"};
  allowed.insert(keys->second.begin(), keys->second.end());
  for (const auto& [key, value] : n.json().items())
    if (!allowed.count(key)) n[key.c_str()].fail("unknown key for a " + type);

  SceneObject o;
  if (type == "mesh")
    o.mesh = read_mesh_object(n, base_dir);
  else
    o.shape = read_shape(n, type);
  o.material = n["material"].string();
  if (!scene.materials.count(o.material)) n["material"].fail("no material named '" + o.material + "'");
  if (n.has("transform")) o.transform = read_transform(n["transform"]);
  if (n.has("transform_end")) {
    o.motion.has_end = true;
    o.motion.end_transform = read_transform(n["transform_end"]);
  }
  if (n.has("velocity")) o.motion.velocity = vec3f(n["velocity"]);
  if (n.has("casts_shadows")) o.casts_shadows = n["casts_shadows"].boolean();
  return o;
}

}  // namespace

namespace detail {

Json parse_scene_json(std::string_view text, const std::string& name) {
  Json doc;
  LocatingParser parser(doc, name);
  try {
    Json::sax_parse(text.begin(), text.end(), &parser);
  } catch (const Json::exception& e) {
    // e.what() reads "[json.exception.parse_error.101] parse error at line 3, column 5: ..." or
    // "[json.exception.out_of_range.406] number overflow parsing '1e999'"; keep the part after the bracket.
    std::string what = e.what();
    const auto bracket = what.find("] ");
    if (bracket != std::string::npos) what = what.substr(bracket + 2);
    throw InvalidInput(located(at_byte(name, static_cast<long long>(parser.error_byte)), what));
  }
  return doc;
}

Scene scene_from_json(const Json& doc, const std::string& name, const std::filesystem::path& base_dir) {
  Scene scene;
  scene.name = name;
  const Node root(doc, "", scene.name);
  root.only({"image", "camera", "ambient", "lights", "materials", "objects", "description", "animation"});
  if (root.has("image")) read_image_settings(root["image"], scene.image);
  if (root.has("camera")) read_camera(root["camera"], scene.camera);
  if (root.has("ambient")) scene.ambient = root["ambient"].color();
  if (root.has("lights")) {
    const Node lights = root["lights"];
    lights.expect_array();
    for (size_t i = 0; i < lights.size(); ++i) scene.lights.push_back(read_light(lights.item(i)));
  }
  if (root.has("materials")) {
    const Node materials = root["materials"];
    if (!materials.json().is_object()) materials.fail("expected an object of named materials");
    for (const auto& [key, value] : materials.json().items()) {
      const Node material = materials[key.c_str()];
      scene.materials[key] = read_material(material, base_dir);
      if (material.has("shader")) scene.shaders[key] = read_shader(material["shader"], base_dir);
    }
  }
  const Node objects = root["objects"];
  objects.expect_array(1);
  for (size_t i = 0; i < objects.size(); ++i) scene.objects.push_back(read_object(objects.item(i), scene, base_dir));
  return scene;
}

}  // namespace detail

Scene parse_scene(std::string_view text, const std::string& name, const std::filesystem::path& base_dir) {
  const AnimatedScene animated(text, name, base_dir);
  return animated.at(animated.animation().first);
}

Camera SceneCamera::camera(double aspect, double near, double far) const {
  Camera c;
  c.eye = eye;
  c.center = center;
  c.up = up;
  c.fovy = radians(fovy);
  c.aspect = aspect;
  c.near = near;
  c.far = far;
  c.orthographic = orthographic;
  c.ortho_height = ortho_height;
  return c;
}

Scene load_scene(const std::filesystem::path& path) {
  return parse_scene(read_file(path), path.string(), path.parent_path());
}

}  // namespace tessera
