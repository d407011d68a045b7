#pragma once
// Volume<T>: a 3D rectilinear grid of voxels (the notes' volume data), with spacing and origin in world units.
//
// Voxel (x, y, z) sits at world point origin + spacing * (x, y, z); x varies fastest in memory, then y, then z
// (index = x + nx * (y + ny * z)), as raw CT/MRI files store them. Values between voxels are trilinear.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include "tessera/core/error.hpp"
#include "tessera/core/memory.hpp"
#include "tessera/image/image.hpp"
#include "tessera/math/types.hpp"

namespace tessera {

/// Voxel types the readers produce.
enum class VoxelType { uint8, uint16, int16, float32 };

/// The name used by the CLI and NRRD ("uint8", "uint16", "int16", "float32").
std::string voxel_type_name(VoxelType type);
/// Parses a voxel type name (also NRRD's aliases "uchar", "ushort", "short", "float"). Throws InvalidInput.
VoxelType parse_voxel_type(const std::string& name);
/// Bytes per voxel.
size_t voxel_size(VoxelType type);

/// The largest voxel count a volume may have (2^34, 16 Gi voxels): larger headers are rejected as hostile.
inline constexpr uint64_t kMaxVoxels = uint64_t(1) << 34;

/// Checks dims (each >= 1) and returns their product. Throws InvalidInput when a size is < 1 or the product exceeds
/// kMaxVoxels (so that a hostile header cannot overflow a size computation).
uint64_t checked_voxel_count(const glm::ivec3& dims);

/// A grid of dims.x x dims.y x dims.z voxels of type T.
template <class T>
class Volume {
 public:
  using Value = T;
  /// An empty volume (0 voxels).
  Volume() = default;
  /// A volume filled with `value`. Throws InvalidInput for non-positive or absurd dims.
  explicit Volume(const glm::ivec3& dims, T value = T{}, const Vec3& spacing = Vec3(1.0),
                  const Vec3& origin = Vec3(0.0))
      : dims_(dims), spacing_(spacing), origin_(origin) {
    voxels_.assign(size_t(checked_voxel_count(dims)), value);
    if (!(spacing.x > 0 && spacing.y > 0 && spacing.z > 0))
      throw InvalidInput(fmt::format("volume spacing must be positive, got {},{},{}", spacing.x, spacing.y, spacing.z));
  }

  const glm::ivec3& dims() const { return dims_; }
  const Vec3& spacing() const { return spacing_; }
  const Vec3& origin() const { return origin_; }
  void set_spacing(const Vec3& spacing) { spacing_ = spacing; }
  void set_origin(const Vec3& origin) { origin_ = origin; }
  size_t voxel_count() const { return voxels_.size(); }
  bool empty() const { return voxels_.empty(); }

  /// Linear index of voxel (x, y, z); no bounds check.
  size_t index(int x, int y, int z) const {
    return size_t(x) + size_t(dims_.x) * (size_t(y) + size_t(dims_.y) * size_t(z));
  }
  /// Voxel (x, y, z); no bounds check.
  T& operator()(int x, int y, int z) { return voxels_[index(x, y, z)]; }
  const T& operator()(int x, int y, int z) const { return voxels_[index(x, y, z)]; }
  /// Voxel (x, y, z) with coordinates clamped to the grid (the border value repeats outside).
  T clamped(int x, int y, int z) const {
    return (*this)(std::clamp(x, 0, dims_.x - 1), std::clamp(y, 0, dims_.y - 1), std::clamp(z, 0, dims_.z - 1));
  }
  /// All voxels in memory order.
  std::span<T> voxels() { return voxels_; }
  std::span<const T> voxels() const { return voxels_; }

  /// The trilinear value at continuous voxel coordinates p (voxel centers at integers), clamped to the grid.
  /// Interpolated in double: the difference of two finite floats can overflow a float (values of both signs near
  /// its limit), while the interpolated value, between the corners', always fits one.
  float sample(const Vec3f& p) const {
    const float fx = std::clamp(p.x, 0.0f, float(dims_.x - 1)), fy = std::clamp(p.y, 0.0f, float(dims_.y - 1)),
                fz = std::clamp(p.z, 0.0f, float(dims_.z - 1));
    const int x0 = std::min(int(fx), std::max(dims_.x - 2, 0)), y0 = std::min(int(fy), std::max(dims_.y - 2, 0)),
              z0 = std::min(int(fz), std::max(dims_.z - 2, 0));
    const int x1 = std::min(x0 + 1, dims_.x - 1), y1 = std::min(y0 + 1, dims_.y - 1),
              z1 = std::min(z0 + 1, dims_.z - 1);
    const double tx = fx - float(x0), ty = fy - float(y0), tz = fz - float(z0);
    const auto v = [&](int x, int y, int z) { return double((*this)(x, y, z)); };
    const double c00 = v(x0, y0, z0) + tx * (v(x1, y0, z0) - v(x0, y0, z0));
    const double c10 = v(x0, y1, z0) + tx * (v(x1, y1, z0) - v(x0, y1, z0));
    const double c01 = v(x0, y0, z1) + tx * (v(x1, y0, z1) - v(x0, y0, z1));
    const double c11 = v(x0, y1, z1) + tx * (v(x1, y1, z1) - v(x0, y1, z1));
    const double c0 = c00 + ty * (c10 - c00), c1 = c01 + ty * (c11 - c01);
    return float(c0 + tz * (c1 - c0));
  }

  /// The gradient at voxel (x, y, z) in world units: central differences inside, one-sided differences on the border
  /// (a dimension of size 1 gives 0). In double: in float it overflows to inf for finite values of both signs near
  /// float's limit, or large values over small spacings (marching cubes normalized it to NaN normals).
  Vec3 gradient(int x, int y, int z) const {
    const auto diff = [&](int axis) {
      glm::ivec3 lo(x, y, z), hi(x, y, z);
      lo[axis] = std::max(lo[axis] - 1, 0);
      hi[axis] = std::min(hi[axis] + 1, dims_[axis] - 1);
      if (hi[axis] == lo[axis]) return 0.0;
      return (double((*this)(hi.x, hi.y, hi.z)) - double((*this)(lo.x, lo.y, lo.z))) /
             (double(hi[axis] - lo[axis]) * spacing_[axis]);
    };
    return {diff(0), diff(1), diff(2)};
  }

  /// World position of continuous voxel coordinates p.
  Vec3 to_world(const Vec3& p) const { return origin_ + spacing_ * p; }
  /// Continuous voxel coordinates of world point w.
  Vec3 to_voxel(const Vec3& w) const { return (w - origin_) / spacing_; }

 private:
  glm::ivec3 dims_{0};
  Vec3 spacing_{1.0};
  Vec3 origin_{0.0};
  RawVector<T> voxels_;  // huge pages for large volumes: filling 64 MiB of 4 KiB pages costs more than the filling
};

/// A volume of any of the reader types.
using AnyVolume = std::variant<Volume<uint8_t>, Volume<uint16_t>, Volume<int16_t>, Volume<float>>;

/// The voxel type held by v.
VoxelType voxel_type(const AnyVolume& v);
/// The volume's values as float (same dims, spacing, origin).
Volume<float> to_float(const AnyVolume& v);
/// to_float() of a volume that is no longer needed: a float volume is moved, not copied (half the peak memory), and
/// integer voxels are freed once converted; `v` is left empty.
Volume<float> to_float(AnyVolume&& v);
/// Dims, spacing and origin of any volume.
const glm::ivec3& dims_of(const AnyVolume& v);
const Vec3& spacing_of(const AnyVolume& v);
const Vec3& origin_of(const AnyVolume& v);

/// Smallest and largest voxel value. Precondition: the volume is not empty (throws InvalidInput otherwise).
template <class T>
std::pair<double, double> value_range(const Volume<T>& v);

/// Counts voxels in `bins` equal bins over [lo, hi]; values outside go to the first or last bin. Throws InvalidInput
/// for bins < 1 or lo >= hi.
template <class T>
std::vector<uint64_t> histogram(const Volume<T>& v, int bins, double lo, double hi);

/// An axis of the grid.
enum class Axis { x = 0, y = 1, z = 2 };
/// Parses "x", "y" or "z". Throws InvalidInput.
Axis parse_axis(const std::string& text);

/// The plane `index` across `axis` as a float image: for Z the pixel (i, j) is voxel (i, j, index); for Y it is
/// (i, index, j); for X it is (index, i, j). Throws InvalidInput when index is outside the grid.
template <class T>
DepthImage slice(const Volume<T>& v, Axis axis, int index);

}  // namespace tessera
