#pragma once
// Drawing one mesh through the rasterizer: the one library renderer of a mesh, called by `tessera raster`, the
// examples' mesh pictures and the viewer. A MeshView prepares a PolyMesh once (normals, an inside-out winding turned
// outward, triangulation, facets, vertex arrays, polygon edges, bounds) and renders it through raster3d for any camera
// and image size: the fixed-function pipeline (unlit, flat, Gouraud or Phong shading, the normals as colors, a
// wireframe, culling, two-sided lighting, the z-buffer or the painter's algorithm, blended opacity), or with maps the
// per-pixel surface shaders (texture, bump and environment maps, a dynamic cube map, shadow maps or shadow volumes, a
// floor). Pictures are anti-aliased by jittered frames averaged (the accumulation buffer) and/or supersampled and
// box-filtered. Also the helpers it and the scene rasterizer share: split facets, polygon edges, sphere framing, a
// shadow map fitted to the casters.
#include <cstdint>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "tessera/image/image.hpp"
#include "tessera/image/texture.hpp"
#include "tessera/math/camera.hpp"
#include "tessera/mesh/measure.hpp"
#include "tessera/mesh/poly_mesh.hpp"
#include "tessera/raster3d/context.hpp"
#include "tessera/raster3d/shadow_map.hpp"

namespace tessera {

class Progress;

/// How a mesh's shadows are drawn: a shadow map fitted to the mesh (the notes' 2-pass z-buffer), or the mesh's
/// stencil shadow volume counted in front of the surface (z-pass) or behind it (z-fail: right with the eye in shadow,
/// needs a perspective camera, its far plane at infinity).
enum class ShadowMethod { map, zpass, zfail };

/// Every triangle with its own three corners (positions, and the colors and uvs where the mesh has them), each corner's
/// normal the triangle's unit face normal (b - a) x (c - a) (counterclockwise is the front). A degenerate triangle,
/// which covers no pixel, gets (0, 0, 1). Flat shading then shows the facets, where OpenGL's flat model would light
/// each triangle at its last vertex's normal.
TriMesh split_faceted(const TriMesh& mesh);

/// The polygon edges (not the triangulation's diagonals), each once as (smaller, larger) vertex index, sorted.
std::vector<std::pair<uint32_t, uint32_t>> polygon_edges(const PolyMesh& mesh);

/// The distance from a sphere's center at which the sphere of `radius` fills a view cone of half-angle `half_angle`
/// (radians) times `margin`: margin * radius / sin(half_angle). At margin 1 the cone touches the sphere; above 1 the
/// sphere lies inside with room to spare (its angular radius is asin(sin(half_angle) / margin)).
double sphere_fit_distance(double radius, double half_angle, double margin);

/// `camera` (its fovy kept) looking at the sphere (center, radius) from `direction` (any length, from the center
/// toward the eye) at sphere_fit_distance(radius, fovy / 2, margin); near and far 1.5 radii either side of the
/// center, near at least 1/1000 of the distance.
Camera frame_sphere(Camera camera, const Vec3& center, double radius, const Vec3& direction, double margin);

/// The shadow map of a light for the casters in the box [lo, hi] (world space), `size` texels square: orthographic
/// along `light` for a directional light (`point` false: `light` is the direction toward it), else from the point
/// `light`: one perspective view, or six faces of size/2 around a light among the casters (ShadowMap::point).
raster3d::ShadowMap fitted_shadow_map(const Vec3& light, bool point, const Vec3& lo, const Vec3& hi, int size);

/// Where sample s of a pixel's n samples lies in the pixel, in [0, 1)^2 with y down the image: the pixel center for
/// n = 1 (the unsampled picture), else Kensler's correlated multi-jittered pattern `pattern`, stratified in a
/// ceil(sqrt n) grid and in 1/n strata along each axis (raytrace/sampling.hpp).
Vec2 pixel_sample(int s, int n, uint32_t pattern);

/// `projection` moved on screen so that the pipeline's pixel centers see the image at `sample` (a pixel_sample) of
/// each pixel of a width x height image: clip x += (1 - 2 sample.x) w / width, clip y -= (1 - 2 sample.y) w / height.
Mat4 jittered_projection(const Mat4& projection, const Vec2& sample, int width, int height);

/// The mean of each s x s block of `image` (a box filter; s = 1: the image itself). The size is divided by s, rounded
/// down.
ImageRGB downsample(const ImageRGB& image, int s);

/// How a mesh view shades the surface. unlit: the color alone; flat: one normal per polygon (its facets show, whatever
/// the file's normals); gouraud: lit at the vertices, colors interpolated; phong: normals interpolated, lit per
/// pixel; normals: unlit, each vertex colored by its unit normal n as (n + 1) / 2 (the viewer's false colors).
enum class MeshShading { unlit, flat, gouraud, phong, normals };

/// Whether a mesh view draws the polygon edges: not at all, over the surface (pulled toward the eye by
/// MeshViewOptions::wire_depth_offset so that the surface under them does not hide them), or alone (every edge, no
/// surface).
enum class MeshWireframe { none, over, alone };

/// Where a mesh view's light is: over the viewer's upper-left shoulder (the direction (-0.4, 0.6, 1) in eye space,
/// moving with the camera), a world-space direction toward the light, or a world-space point.
enum class MeshLightKind { viewer, directional, point };

/// A mesh view's one white light.
struct MeshLight {
  MeshLightKind kind = MeshLightKind::viewer;
  Vec3 vector{0.0};   ///< directional: toward the light (any nonzero length); point: its position
  float diffuse = 1;  ///< its diffuse intensity (the specular intensity stays 1)
};

/// Everything a MeshView draws with. Options marked "(prepared)" are part of the mesh's preparation: changing them
/// through MeshView::set_options prepares again (the others are read by every render).
struct MeshViewOptions {
  MeshShading shading = MeshShading::gouraud;  ///< (prepared: flat and normals need their own arrays)
  Vec3f color{0.8f};                           ///< the surface color (ambient and diffuse, as GL_COLOR_MATERIAL)
  std::vector<Vec3f> face_colors;  ///< per polygon, replacing `color` (those beyond its end keep it; prepared)
  /// The surface's highlight: a white plastic specular of this strength and shininess (the color, or the face
  /// colors, are ambient and diffuse).
  float specular = 0.4f, shininess = 32;
  /// A material instead of the color and highlight (its own ambient and diffuse; the colors are then ignored).
  std::optional<raster3d::Material> material;
  raster3d::SpecularModel specular_model = raster3d::SpecularModel::blinn;
  Vec3f background{0.0f};
  MeshLight light;
  MeshWireframe wireframe = MeshWireframe::none;
  /// The edges' color; by default dark on a light background (channels summing over 1.5), light on a dark one.
  std::optional<Vec3f> wire_color;
  /// How far the edges are pulled toward the eye: z_clip -= offset w (glPolygonOffset's job).
  double wire_depth_offset = 0x1p-14;
  raster3d::CullMode cull = raster3d::CullMode::none;
  /// Two-sided lighting (OpenGL's, done in two culled passes): the back faces lit with the flipped normal and colored
  /// `back_shade` times darker; `cull` is then ignored.
  bool two_sided = false;
  float back_shade = 0.55f;
  raster3d::HiddenSurface hidden_surface = raster3d::HiddenSurface::zbuffer;
  /// Below 1: the triangles sorted far to near for each camera and blended "over" what lies behind them.
  double opacity = 1;
  /// Jittered frames averaged per picture (the accumulation buffer's anti-aliasing), at pixel_sample(s, samples,
  /// kSamplePattern) each.
  int samples = 1;
  /// Supersampling: drawn at s times the size in each axis and box-filtered down (downsample); the edges are drawn at
  /// s x s one-pixel offsets so that they stay a pixel wide.
  int supersample = 1;
  /// The maps, already loaded (a texture and a bump map need the mesh's uvs). With any of them, or shadows, a floor or
  /// env_cube, the surface is drawn per pixel by raster3d's surface shaders with Phong shading: no wireframe, opacity,
  /// face colors, two-sided lighting or painter's algorithm then.
  std::shared_ptr<const Texture2D> texture, bump;
  double bump_scale = 0.01;  ///< the height of a white bump texel, as a fraction of the mesh's bounding-box diagonal
  std::shared_ptr<const EnvironmentMap> environment;  ///< a lat-long image the surface reflects, and the background
  double reflect = 0.6;                               ///< how much of the environment the surface reflects
  bool env_cube = false;  ///< reflect the surroundings (floor, environment) through a cube map drawn from the center
  bool shadows = false;   ///< the mesh's shadow, on itself and the floor
  ShadowMethod shadow_method = ShadowMethod::map;
  int shadow_size = 2048;  ///< the shadow map's size in texels
  bool floor = false;      ///< a light gray floor under the mesh, three times its size, to receive its shadow
  int up_axis = 1;         ///< the model's up axis (0 x, 1 y, 2 z): the floor's normal
  /// Turn a closed, consistently oriented mesh whose faces wind inward (a negative volume) and which has no normals of
  /// its own outward before drawing (prepared).
  bool turn_outward = true;

  /// A program the surface is drawn through instead of `shading` (a glsl::Program, libs/glsl; Context::use_program):
  /// its built-ins read the view's state (gl_LightSource[0] the light, gl_FrontMaterial the color's plastic, the
  /// camera's matrices). Not with the maps; the wireframe's lines stay fixed-function.
  std::shared_ptr<raster3d::ContextProgram> program;

  /// Whether the per-pixel surface shaders draw (a map, shadows, a floor or env_cube).
  bool maps() const { return texture || bump || environment || shadows || floor || env_cube; }
};

/// The --samples pattern of the mesh view (one for every pixel: the jittered frames move the whole picture).
inline constexpr uint32_t kSamplePattern = 0x5eed;

/// A rendered mesh view: the picture, its depth and how many pixels the mesh covers.
struct MeshPicture {
  ImageRGB color;
  /// The nearest depth of each pixel's samples as window z in [0, 1] (1 = background). Under the painter's algorithm,
  /// which keeps no depth, 0 where the mesh covers the pixel.
  DepthImage depth;
  size_t covered = 0;  ///< pixels some sample of the mesh covered (the floor and environment do not count)
};

/// One mesh prepared for drawing, then rendered for any number of cameras (the viewer's frame loop) without preparing
/// again. Its fixed-function context is kept between renders of the same size, so one view renders on one thread at a
/// time (views are movable, not copyable).
class MeshView {
 public:
  /// Prepares `mesh`: normals where it has none (Mesh's vertex normals), turned outward when options.turn_outward
  /// says so, triangulated (triangulate_polygon), the facets of flat shading, the vertex arrays, the polygon edges
  /// and the bounds. Throws InvalidInput when a texture or bump map is given and the mesh has no uvs.
  explicit MeshView(PolyMesh mesh, MeshViewOptions options = {});

  /// Changes the options; re-prepares only what the prepared ones (shading between flat, normals and the others,
  /// face_colors, turn_outward) need. Throws as the constructor.
  void set_options(MeshViewOptions options);
  const MeshViewOptions& options() const { return options_; }

  /// The mesh's bounding box (for framing a camera).
  const Bounds3& bounds() const { return bounds_; }
  /// The box of what is drawn: the mesh's, and the floor's when options().floor (for the far plane).
  Bounds3 scene_bounds() const;
  /// The number of triangles drawn.
  size_t triangle_count() const { return triangles_; }
  /// Whether the preparation turned the mesh outward (see MeshViewOptions::turn_outward).
  bool turned_outward() const { return turned_outward_; }

  /// Renders the mesh through `camera` (its aspect as given) at width x height; `progress`, when given, advances once
  /// per jittered sample. A mesh without faces gives the background. Throws InvalidInput for a bad size, z-fail shadow
  /// volumes under an orthographic camera, or env_cube with nothing to reflect (no floor or environment).
  MeshPicture render(const Camera& camera, int width, int height, Progress* progress = nullptr) const;

  /// Renders the mesh through `camera` into `out` at out's size, each pixel render(...).color as 8-bit RGBA
  /// (raster3d::to_color8: alpha 255), the same bytes. When one sample is drawn (samples and supersample 1, the
  /// viewer's frame loop), the rasterizer's 8-bit colors are copied straight into `out`, rows in parallel: no float
  /// picture, no depth image, no coverage count. Otherwise (and for a mesh without faces) render() is converted.
  /// Throws as render().
  void render_into(const Camera& camera, ImageRGBA8& out, Progress* progress = nullptr) const;

 private:
  void prepare();
  /// edge_vertices_ and edge_lines_ from mesh_ when options_ ask for a wireframe, else empty.
  void prepare_edges();
  /// render(), or with `direct` (one sample drawn) the frame's colors copied into *direct and an empty picture.
  MeshPicture render_impl(const Camera& camera, int width, int height, Progress* progress, ImageRGBA8* direct) const;

  PolyMesh source_;  // as given
  PolyMesh mesh_;    // with normals, turned outward where asked
  MeshViewOptions options_;
  Bounds3 bounds_;
  size_t triangles_ = 0;
  bool turned_outward_ = false;
  raster3d::VertexArrays arrays_;  // the triangles as drawn (faceted for flat shading)
  // The polygon edges, made while a wireframe is asked for: mesh_'s positions in float, two of them a line.
  raster3d::VertexArrays edge_vertices_;
  std::vector<uint32_t> edge_lines_;
  mutable std::unique_ptr<raster3d::Context> context_;  // kept between renders: no framebuffer allocated per frame
};

/// Refuses up front (MemoryBudgetError, core/memory_budget.hpp) a width x height render with `options` whose memory
/// would exceed the budget: per pixel the framebuffer's color and depth, the samples' sum and depth and an 8-bit copy
/// (44 bytes measured), times supersample^2; with shadow mapping 6 bytes per shadow texel (a point light among the
/// casters has six faces of half the size). MeshView::render checks it; a caller may check before preparing anything.
void check_mesh_view_memory(int width, int height, const MeshViewOptions& options);

/// One picture of `mesh` through `camera` at width x height: MeshView(mesh, options).render(camera, width, height).
MeshPicture render_mesh(const PolyMesh& mesh, const Camera& camera, int width, int height,
                        const MeshViewOptions& options = {});

}  // namespace tessera
