// libFuzzer target for the algorithms on volumes (`tessera volume contour/isosurface/render`). The first 16 bytes
// are parameters, the rest are voxels decoded by decode_raw:
//   0-2  dims, 1..16 each            3  voxel type, byte order, marching cubes mode (classic/topological, normals)
//   4-6  spacing per axis (1/8..2, or 1e300: a box beyond the finite numbers is refused)
//   7    origin and camera direction  8-11  iso value (a float; any bits)
//   12   image size (1..8 x 1..8), MIP, shading, empty-space skipping, SIMD
//   13   transfer function (automatic, a preset, or points from the voxel range) and early termination
//   14   block size, orthographic camera    15  ray step (0 = default, a fraction of the diagonal, or hostile values)
// On what decodes it runs marching cubes (options.iso from bytes 8-11), marching squares on a slice across each axis,
// and the volume renderer. Steps that would take more than 4096 samples per ray are replaced by the default step,
// except those so small that render_volume must refuse them (over kMaxSamplesPerRay), so one input stays well under
// a second; the memory budget is 256 MiB.
// tessera::Error is the expected outcome (a volume or step that is refused); anything else (a crash, another
// exception, a sanitizer report, a hang) is a bug, and so is a broken invariant (__builtin_trap): a mesh vertex,
// normal or contour point that is not finite, triangle indices out of range, or a pixel that is NaN or negative.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string_view>

#include "tessera/core/error.hpp"
#include "tessera/core/memory_budget.hpp"
#include "tessera/volume/marching_cubes.hpp"
#include "tessera/volume/marching_squares.hpp"
#include "tessera/volume/volume.hpp"
#include "tessera/volume/volume_io.hpp"
#include "tessera/volume/volume_render.hpp"

namespace {

using namespace tessera;

void check(bool ok) {
  if (!ok) __builtin_trap();
}

bool finite(const Vec3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

void isosurface(const Volume<float>& volume, float iso, uint8_t mode) {
  MarchingCubesOptions options;
  options.iso = iso;
  options.topological = mode / 8 % 2;
  options.normals = mode / 16 % 2;
  options.slab_layers = 1 + mode / 32 % 4;
  const PolyMesh mesh = marching_cubes(volume, options);
  for (const Vec3& p : mesh.positions) check(finite(p));
  for (const Vec3& n : mesh.normals) check(finite(n));
  for (uint32_t v : mesh.face_vertices) check(v < mesh.vertex_count());
  check(mesh.is_triangle_mesh());
}

void contours(const Volume<float>& volume, float iso) {
  for (Axis axis : {Axis::x, Axis::y, Axis::z}) {
    const int n = volume.dims()[int(axis)];
    for (const Polyline& line : marching_squares(slice(volume, axis, n / 2), iso))
      for (const Vec2& p : line.points) check(std::isfinite(p.x) && std::isfinite(p.y));
  }
}

TransferFunction transfer(const Volume<float>& volume, uint8_t byte, const uint8_t* voxel_bytes) {
  const ValueProfile profile = profile_values(volume);
  switch (byte % 5) {
    case 0:
      return TransferFunction::automatic(profile);
    case 1:
    case 2:
    case 3: {
      const auto& names = TransferFunction::preset_names();
      return TransferFunction::preset(names[size_t(byte % 5 - 1) % names.size()], profile);
    }
    default: {
      // Two to four points spread over the value range, colors and opacities from the first voxel bytes.
      std::vector<TransferFunction::Point> points;
      const int count = 2 + byte / 8 % 3;
      for (int i = 0; i < count; ++i) {
        const float value = float(profile.lo + (profile.hi - profile.lo) * i / (count - 1));
        const float c = float(voxel_bytes[i % 4]) / 255.0f * (byte / 64 % 2 ? TransferFunction::kMaxColor : 1.0f);
        points.push_back(
            {value, Vec3f(c, 1.0f - float(i) / float(count), 0.5f), float(voxel_bytes[(i + 1) % 4]) / 255});
      }
      return TransferFunction(points);
    }
  }
}

void render(const Volume<float>& volume, const uint8_t* p, const uint8_t* voxel_bytes) {
  VolumeRenderOptions o;
  o.width = 1 + p[12] % 8;
  o.height = 1 + p[12] / 8 % 8;
  o.mip = p[12] / 64 % 2;
  o.shading = p[12] / 128 % 2;
  o.skip_empty = p[13] / 32 % 2;
  o.simd = p[14] / 128 % 2;
  o.termination = 0.5f + float(p[13] / 64) / 6.0f;  // 0.5 .. 1
  o.block = 1 + p[14] % 8;
  o.transfer = transfer(volume, p[13], voxel_bytes);

  const Vec3 lo = volume.origin(), hi = volume.to_world(Vec3(volume.dims() - 1));
  const double diagonal = glm::length(hi - lo);
  // Directions from the box's center: the axes (exactly along a face), a diagonal, one inside the box.
  const Vec3 directions[] = {{0, 0, 1}, {1, 0, 0}, {0, -1, 0}, {1, 1, 1}, {0.3, 0.2, 0.1}, {-1, 2, 0.5}};
  o.camera.center = 0.5 * (lo + hi);
  // Within 1e150 of the center (inside the box of a huge volume): Camera's frame overflows for distances past 1e154.
  o.camera.eye = o.camera.center + directions[p[7] / 4 % 6] * std::clamp(2 * diagonal, 1e-3, 1e150);
  o.camera.up = p[7] / 4 % 6 == 2 ? Vec3(0, 0, 1) : Vec3(0, 1, 0);
  o.camera.orthographic = p[14] / 8 % 2;
  o.camera.ortho_height = std::max(diagonal, 1e-3);

  const uint8_t s = p[15];
  const double samples = s < 200 ? double(s % 64 + 1) * 64 : 0;  // up to 4096 samples per ray
  if (s < 200)
    o.step = float(diagonal / samples);
  else if (s < 210)
    o.step = 0;
  else if (s < 220)
    o.step = float(diagonal / double(VolumeRenderOptions::kMaxSamplesPerRay) / 4);  // refused
  else if (s < 230)
    o.step = -1;
  else if (s < 240)
    o.step = NAN;
  else if (s < 250)
    o.step = INFINITY;
  else
    o.step = 1e-9f;
  if (o.step > 0 && std::isfinite(o.step) && diagonal / o.step > 4096 &&
      diagonal / o.step <= double(VolumeRenderOptions::kMaxSamplesPerRay))
    o.step = 0;  // a legal but slow step: the default one instead

  const ImageRGB image = render_volume(volume, o);
  check(image.width() == o.width && image.height() == o.height);
  for (const glm::vec3& px : image.pixels())
    for (int c = 0; c < 3; ++c) check(!std::isnan(px[c]) && px[c] >= 0);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 16) return 0;
  MemoryBudget::set_limit(uint64_t(256) << 20);
  const uint8_t* p = data;
  RawLayout layout;
  layout.dims = glm::ivec3(1 + p[0] % 16, 1 + p[1] % 16, 1 + p[2] % 16);
  layout.type = VoxelType(p[3] % 4);
  layout.endian = p[3] / 4 % 2 ? Endian::big : Endian::little;
  for (int a = 0; a < 3; ++a) layout.spacing[a] = p[4 + a] % 16 == 15 ? 1e300 : double(1 + p[4 + a] % 16) / 8;
  layout.origin = Vec3(p[7] % 4 == 3 ? -1e300 : double(p[7] % 4) - 1);
  float iso;
  std::memcpy(&iso, p + 8, sizeof iso);
  const std::string_view voxels(reinterpret_cast<const char*>(data) + 16, size - 16);
  static const uint8_t kNoBytes[4] = {128, 64, 255, 0};
  const uint8_t* voxel_bytes = voxels.size() >= 4 ? data + 16 : kNoBytes;
  try {
    const Volume<float> volume = to_float(decode_raw(voxels, layout, "fuzz.raw"));
    try {
      isosurface(volume, iso, p[3]);
      contours(volume, iso);
    } catch (const Error&) {
    }
    render(volume, p, voxel_bytes);
  } catch (const Error&) {
  }
  return 0;
}
