// Program: compiling, uniforms by name, texture units and the compatibility built-ins' values.
#include <glm/gtc/matrix_inverse.hpp>

#include "module.hpp"
#include "tessera/core/atomic_file.hpp"
#include "tessera/core/parse.hpp"
#include "tessera/raster3d/lighting.hpp"

namespace tessera::glsl {
namespace {

/// The slot of uniform `name`, or of element 0 when `name` is an array's name; null when there is none.
UniformSlot* find_uniform(ProgramModule& m, std::string_view name, bool builtin) {
  for (UniformSlot& s : m.uniforms)
    if (s.builtin == builtin &&
        (s.name == name || (s.name.size() == name.size() + 3 && s.name.starts_with(name) && s.name.ends_with("[0]"))))
      return &s;
  return nullptr;
}

/// The array a slot is an element of ("w[2]" -> "w", 2), or ("", -1).
std::pair<std::string, int> array_element(const std::string& name) {
  if (name.empty() || name.back() != ']') return {"", -1};
  const size_t open = name.rfind('[');
  return {name.substr(0, open), std::stoi(name.substr(open + 1))};
}

/// Writes `values` (32-bit words) into the slot of `name` and, past its end, into the following elements of its
/// array. Throws InvalidInput when there are more values than elements.
void write_uniform(ProgramModule& m, std::string_view name, std::span<const uint32_t> values, bool floats,
                   bool builtin) {
  UniformSlot* slot = find_uniform(m, name, builtin);
  if (!slot) {
    // A declared uniform the program does not read ("light.color", "w[2]": the declaration is "light", "w") takes
    // any value and keeps none, as in OpenGL.
    if (m.declared_uniforms.count(std::string(name.substr(0, name.find_first_of(".[")))) > 0) return;
    throw InvalidInput("the program declares no uniform '" + printable(name) + "'");
  }
  if (slot->is_float != floats)
    throw InvalidInput("uniform '" + slot->name + "' takes " + (slot->is_float ? "floats" : "integers") + ", not " +
                       (floats ? "floats" : "integers"));
  const auto [array, first] = array_element(slot->name);
  size_t used = 0;
  for (int e = first; used < values.size(); ++e) {
    if (e != first) {
      const std::string next = array + "[" + std::to_string(e) + "]";
      slot = nullptr;
      for (UniformSlot& s : m.uniforms)
        if (s.name == next) slot = &s;
      if (!slot || first < 0)
        throw InvalidInput("uniform '" + std::string(name) + "' takes " + std::to_string(used) + " values, not " +
                           std::to_string(values.size()));
    }
    const size_t n = std::min(values.size() - used, size_t(slot->components));
    if (e == first && n < size_t(slot->components) && values.size() < size_t(slot->components))
      throw InvalidInput("uniform '" + slot->name + "' takes " + std::to_string(slot->components) + " values, not " +
                         std::to_string(values.size()));
    std::copy_n(values.begin() + ptrdiff_t(used), n, m.uniform_words.begin() + slot->word);
    used += n;
  }
}

std::vector<uint32_t> float_words(std::span<const float> values) {
  std::vector<uint32_t> words(values.size());
  std::memcpy(words.data(), values.data(), values.size() * sizeof(float));
  return words;
}

void set_builtin(ProgramModule& m, const std::string& name, std::span<const float> values) {
  for (UniformSlot& s : m.uniforms)
    if (s.builtin && s.name == name)
      for (int k = 0; k < s.components && k < int(values.size()); ++k)
        std::memcpy(&m.uniform_words[s.word + uint32_t(k)], &values[size_t(k)], sizeof(float));
}

template <class T>
std::span<const float> floats_of(const T& v) {
  return {&v[0][0] + 0, sizeof(T) / sizeof(float)};
}
std::span<const float> floats_of_vec(const float* v, size_t n) { return {v, n}; }

/// The compatibility built-ins of the OpenGL 2.1 specification, section 2.15.3 (and the derived products), from the
/// state.
void apply_fixed_function(ProgramModule& m) {
  const FixedFunctionState& f = m.fixed;
  const Mat4f mv = f.model_view, p = f.projection;
  const Mat4f mvp = raster3d::gl_matrix_product(p, mv);  // as Mesa forms it: ftransform() matches the fixed function
  const Mat4f identity(1.0f);
  const auto matrices = [&](const std::string& name, const Mat4f& x) {
    const Mat4f inv = glm::inverse(x);
    set_builtin(m, name, floats_of(x));
    set_builtin(m, name + "Inverse", floats_of(inv));
    set_builtin(m, name + "Transpose", floats_of(glm::transpose(x)));
    set_builtin(m, name + "InverseTranspose", floats_of(glm::transpose(inv)));
  };
  matrices("gl_ModelViewMatrix", mv);
  matrices("gl_ProjectionMatrix", p);
  matrices("gl_ModelViewProjectionMatrix", mvp);
  for (int t = 0; t < 32; ++t) matrices("gl_TextureMatrix[" + std::to_string(t) + "]", identity);
  const glm::mat3 normal = glm::inverseTranspose(glm::mat3(mv));
  set_builtin(m, "gl_NormalMatrix", floats_of(normal));
  const float depth_range[3] = {0.0f, 1.0f, 1.0f};
  set_builtin(m, "gl_DepthRange.near", floats_of_vec(depth_range, 1));
  set_builtin(m, "gl_DepthRange.far", floats_of_vec(depth_range + 1, 1));
  set_builtin(m, "gl_DepthRange.diff", floats_of_vec(depth_range + 2, 1));
  const auto vec = [&](const std::string& name, const float* v, size_t n) { set_builtin(m, name, {v, n}); };
  const auto scalar = [&](const std::string& name, float v) { set_builtin(m, name, {&v, 1}); };
  vec("gl_LightModel.ambient", &f.light_model_ambient[0], 4);
  const FixedFunctionState::Material* materials[2] = {&f.front_material, &f.back_material};
  const char* sides[2] = {"Front", "Back"};
  for (int side = 0; side < 2; ++side) {
    const FixedFunctionState::Material& mat = *materials[side];
    const std::string material = std::string("gl_") + sides[side] + "Material.";
    vec(material + "emission", &mat.emission[0], 4);
    vec(material + "ambient", &mat.ambient[0], 4);
    vec(material + "diffuse", &mat.diffuse[0], 4);
    vec(material + "specular", &mat.specular[0], 4);
    scalar(material + "shininess", mat.shininess);
    const Vec4f scene(Vec3f(mat.emission) + Vec3f(mat.ambient) * Vec3f(f.light_model_ambient), mat.diffuse.w);
    vec(std::string("gl_") + sides[side] + "LightModelProduct.sceneColor", &scene[0], 4);
    for (int i = 0; i < 8; ++i) {
      const FixedFunctionState::Light& light = f.lights[i];
      const std::string product = std::string("gl_") + sides[side] + "LightProduct[" + std::to_string(i) + "].";
      const Vec4f ambient = mat.ambient * light.ambient, diffuse = mat.diffuse * light.diffuse,
                  specular = mat.specular * light.specular;
      vec(product + "ambient", &ambient[0], 4);
      vec(product + "diffuse", &diffuse[0], 4);
      vec(product + "specular", &specular[0], 4);
    }
  }
  for (int i = 0; i < 8; ++i) {
    const FixedFunctionState::Light& light = f.lights[i];
    const std::string source = "gl_LightSource[" + std::to_string(i) + "].";
    vec(source + "ambient", &light.ambient[0], 4);
    vec(source + "diffuse", &light.diffuse[0], 4);
    vec(source + "specular", &light.specular[0], 4);
    vec(source + "position", &light.position[0], 4);
    // The half vector of an infinite viewer: the light direction plus the eye's (0, 0, 1), normalized.
    const Vec3f to_light = glm::normalize(Vec3f(light.position));
    const Vec4f half(glm::normalize(to_light + Vec3f(0, 0, 1)), 1.0f);
    vec(source + "halfVector", &half[0], 4);
    vec(source + "spotDirection", &light.spot_direction[0], 3);
    scalar(source + "spotExponent", light.spot_exponent);
    scalar(source + "spotCutoff", light.spot_cutoff);
    scalar(source + "spotCosCutoff", std::cos(glm::radians(light.spot_cutoff)));
    scalar(source + "constantAttenuation", light.constant_attenuation);
    scalar(source + "linearAttenuation", light.linear_attenuation);
    scalar(source + "quadraticAttenuation", light.quadratic_attenuation);
  }
}

}  // namespace

FixedFunctionState::FixedFunctionState() {
  for (int i = 1; i < 8; ++i) lights[i].diffuse = lights[i].specular = Vec4f(0, 0, 0, 1);
}

ShaderSource read_shader(const std::string& path) { return {read_file(path), path}; }

Program::Program() = default;
Program::Program(Program&&) noexcept = default;
Program& Program::operator=(Program&&) noexcept = default;
Program::~Program() = default;

Program Program::compile(const ShaderSource& vertex, const ShaderSource& fragment) {
  Program p;
  p.module_ = compile_module(vertex, fragment);
  apply_fixed_function(*p.module_);
  return p;
}

const std::vector<UniformInfo>& Program::uniforms() const { return module_->user_uniforms; }

bool Program::has_uniform(std::string_view name) const { return find_uniform(*module_, name, false) != nullptr; }

void Program::set_uniform(std::string_view name, std::span<const float> values) {
  const std::vector<uint32_t> words = float_words(values);
  write_uniform(*module_, name, words, true, false);
}

void Program::set_uniform(std::string_view name, std::span<const int> values) {
  const UniformSlot* slot = find_uniform(*module_, name, false);
  if (slot && (slot->type == BasicType::sampler_2d || slot->type == BasicType::sampler_cube))
    for (const int unit : values)
      if (unit < 0 || unit >= 16)
        throw InvalidInput("sampler '" + slot->name + "': texture unit " + std::to_string(unit) + " is not in [0, 16)");
  std::vector<uint32_t> words(values.begin(), values.end());
  write_uniform(*module_, name, words, false, false);
}

void Program::set_uniform_text(std::string_view name, std::string_view values) {
  const UniformSlot* slot = find_uniform(*module_, name, false);
  const std::string what = "uniform " + std::string(name);
  const std::vector<double> numbers = parse_doubles(values, 0, what);
  if (!slot || slot->is_float) {
    std::vector<float> floats(numbers.begin(), numbers.end());
    set_uniform(name, floats);
    return;
  }
  std::vector<int> ints;
  for (const double v : numbers) {
    if (v != std::floor(v) || std::abs(v) > 2147483647.0)
      throw InvalidInput(what + ": expected integers, got '" + printable(values) + "'");
    ints.push_back(int(v));
  }
  set_uniform(name, ints);
}

void Program::set_uniform_assignment(std::string_view assignment) {
  const size_t eq = assignment.find('=');
  if (eq == std::string_view::npos || eq == 0 || eq + 1 == assignment.size())
    throw InvalidInput("uniform: expected name=v1,v2,..., got '" + printable(assignment) + "'");
  set_uniform_text(assignment.substr(0, eq), assignment.substr(eq + 1));
}

void Program::bind_texture(int unit, std::shared_ptr<const Texture2D> texture) {
  if (unit < 0 || unit >= 16) throw InvalidInput("texture unit " + std::to_string(unit) + " is not in [0, 16)");
  module_->textures[size_t(unit)] = std::move(texture);
}

void Program::bind_cube_map(int unit, std::shared_ptr<const CubeMap> cube_map) {
  if (unit < 0 || unit >= 16) throw InvalidInput("texture unit " + std::to_string(unit) + " is not in [0, 16)");
  module_->cube_maps[size_t(unit)] = std::move(cube_map);
}

void Program::set_fixed_function(const FixedFunctionState& state) {
  module_->fixed = state;
  apply_fixed_function(*module_);
}

bool Program::discards() const { return module_->fragment.discards; }

raster3d::DrawStats Program::draw_arrays(raster3d::Framebuffer& framebuffer, const raster3d::RasterState& state,
                                         const raster3d::ProgramState& p, const raster3d::VertexAttributes& attributes,
                                         uint32_t vertex_count, std::span<const uint32_t> indices) {
  FixedFunctionState f;
  f.model_view = p.model_view;
  f.projection = p.projection;
  for (int i = 0; i < raster3d::kMaxLights; ++i) {
    const raster3d::Light& light = p.lighting.lights[size_t(i)];
    f.lights[i].position = light.position;
    f.lights[i].ambient = Vec4f(light.ambient, 1);
    f.lights[i].diffuse = Vec4f(light.diffuse, 1);
    f.lights[i].specular = Vec4f(light.specular, 1);
  }
  const raster3d::Material& m = p.lighting.material;
  f.front_material = {Vec4f(m.ambient, 1), Vec4f(m.diffuse, p.alpha), Vec4f(m.specular, 1), Vec4f(m.emission, 1),
                      m.shininess};
  f.back_material = f.front_material;
  f.light_model_ambient = Vec4f(p.lighting.model_ambient, 1);
  f.color = Vec4f(p.color, p.alpha);
  f.normal = p.normal;
  f.tex_coord = Vec4f(p.uv, 0, 1);
  set_fixed_function(f);
  ProgramInputs in;
  in.positions = {attributes.positions, vertex_count};
  if (attributes.normals) in.normals = {attributes.normals, vertex_count};
  if (attributes.colors) in.colors = {attributes.colors, vertex_count};
  if (attributes.uvs) in.uvs = {attributes.uvs, vertex_count};
  return draw_triangles(framebuffer, state, in, indices);
}

}  // namespace tessera::glsl
