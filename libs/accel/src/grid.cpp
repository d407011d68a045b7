// Uniform grid construction: cell resolution by the density rule, cell lists in one flat array (counting sort).
#include "tessera/accel/grid.hpp"

#include <string>

#include "tessera/core/error.hpp"

namespace tessera {

UniformGrid::UniformGrid(std::span<const AABB> prim_bounds, const GridSettings& settings) {
  if (!(settings.density > 0) || settings.max_resolution < 1)
    throw InvalidInput("GridSettings: density must be > 0 and max_resolution >= 1");
  int64_t count = 0;
  for (size_t i = 0; i < prim_bounds.size(); ++i) {
    const AABB& b = prim_bounds[i];
    if (b.empty()) continue;
    for (int a = 0; a < 3; ++a)
      if (!std::isfinite(b.lo[a]) || !std::isfinite(b.hi[a]))
        throw InvalidInput("UniformGrid: primitive " + std::to_string(i) + " has a non-finite box");
    box_.expand(b);
    ++count;
  }
  if (count == 0) return;
  // A flat set of primitives (all in one plane) still needs a box of some thickness.
  const float pad = 1e-5f * std::max({box_.extent().x, box_.extent().y, box_.extent().z, 1e-3f});
  for (int a = 0; a < 3; ++a)
    if (box_.extent()[a] < pad) {
      box_.lo[a] -= pad;
      box_.hi[a] += pad;
    }
  const Vec3f ext = box_.extent();
  // The density rule: about density * N cells in all, roughly cubic.
  const double cells_per_unit = std::cbrt(double(settings.density) * double(count) / (double(ext.x) * ext.y * ext.z));
  for (int a = 0; a < 3; ++a)
    res_[a] = int(std::clamp(std::round(double(ext[a]) * cells_per_unit), 1.0, double(settings.max_resolution)));
  cell_size_ = ext / Vec3f(res_);
  inv_cell_ = Vec3f(res_) / ext;

  // The cells a box overlaps, widened by a thousandth of a cell so that rounding never drops a primitive from the cell
  // where its surface is.
  auto cell_range = [&](const AABB& b, glm::ivec3& lo, glm::ivec3& hi) {
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::clamp(int(std::floor((b.lo[a] - box_.lo[a]) * inv_cell_[a] - 1e-3f)), 0, res_[a] - 1);
      hi[a] = std::clamp(int(std::floor((b.hi[a] - box_.lo[a]) * inv_cell_[a] + 1e-3f)), 0, res_[a] - 1);
    }
  };
  const size_t cells = size_t(res_.x) * res_.y * res_.z;
  offsets_.assign(cells + 1, 0);
  glm::ivec3 lo, hi;
  for (const AABB& b : prim_bounds) {
    if (b.empty()) continue;
    cell_range(b, lo, hi);
    for (int z = lo.z; z <= hi.z; ++z)
      for (int y = lo.y; y <= hi.y; ++y)
        for (int x = lo.x; x <= hi.x; ++x) ++offsets_[size_t((z * res_.y + y) * res_.x + x) + 1];
  }
  for (size_t c = 0; c < cells; ++c) offsets_[c + 1] += offsets_[c];
  prims_.resize(size_t(offsets_[cells]));
  std::vector<int> fill(offsets_.begin(), offsets_.end() - 1);
  for (size_t i = 0; i < prim_bounds.size(); ++i) {
    if (prim_bounds[i].empty()) continue;
    cell_range(prim_bounds[i], lo, hi);
    for (int z = lo.z; z <= hi.z; ++z)
      for (int y = lo.y; y <= hi.y; ++y)
        for (int x = lo.x; x <= hi.x; ++x) prims_[size_t(fill[size_t((z * res_.y + y) * res_.x + x)]++)] = int(i);
  }
}

}  // namespace tessera
