#include "tessera/fractal/dimension.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "tessera/core/error.hpp"

namespace tessera {
namespace {

/// The set pixels' bounding box: columns [x0, x1), rows [y0, y1).
struct PixelBox {
  int x0, y0, x1, y1;
};

PixelBox set_bounds(const Image<uint8_t>& mask) {
  PixelBox box{mask.width(), mask.height(), 0, 0};
  for (int y = 0; y < mask.height(); ++y) {
    const uint8_t* row = mask.row(y);
    for (int x = 0; x < mask.width(); ++x)
      if (row[x] != 0) {
        box.x0 = std::min(box.x0, x), box.x1 = std::max(box.x1, x + 1);
        box.y0 = std::min(box.y0, y), box.y1 = std::max(box.y1, y + 1);
      }
  }
  if (box.x1 == 0) throw InvalidInput("box counting needs at least one set pixel, the image is empty");
  return box;
}

/// Box index of each pixel along one axis: the pixel's center, measured from the bounding box's edge, in boxes of s.
std::vector<int> box_indices(int count, double s) {
  std::vector<int> index(static_cast<size_t>(count));
  for (int i = 0; i < count; ++i) index[size_t(i)] = int(std::floor((i + 0.5) / s));
  return index;
}

int64_t count_boxes(const Image<uint8_t>& mask, const PixelBox& box, double s) {
  const std::vector<int> bx = box_indices(box.x1 - box.x0, s), by = box_indices(box.y1 - box.y0, s);
  const size_t columns = size_t(bx.back()) + 1;
  std::vector<uint8_t> hit(columns * (size_t(by.back()) + 1), 0);
  for (int y = box.y0; y < box.y1; ++y) {
    const uint8_t* row = mask.row(y) + box.x0;
    uint8_t* boxes = hit.data() + size_t(by[size_t(y - box.y0)]) * columns;
    for (size_t x = 0; x < bx.size(); ++x) boxes[bx[x]] |= uint8_t(row[x] != 0);
  }
  return std::count(hit.begin(), hit.end(), uint8_t(1));
}

}  // namespace

BoxCountResult box_counting_dimension(const Image<uint8_t>& mask, const BoxCountOptions& options) {
  if (!(options.min_box >= 1))
    throw InvalidInput(fmt::format("smallest box must be >= 1 pixel, got {}", options.min_box));
  if (!(options.max_box >= 0)) throw InvalidInput(fmt::format("largest box must be >= 0, got {}", options.max_box));
  if (!(options.factor > 1)) throw InvalidInput(fmt::format("box size factor must be > 1, got {}", options.factor));
  const PixelBox box = set_bounds(mask);
  BoxCountResult result;
  result.extent = std::max(box.x1 - box.x0, box.y1 - box.y0);
  const double max_box = options.max_box > 0 ? options.max_box : double(result.extent);
  // Sizes from the largest down, each max_box / factor^k, so that rounding does not drift along the sequence.
  for (int k = 0;; ++k) {
    const double s = max_box / std::pow(options.factor, k);
    if (s < options.min_box * (1 - 1e-12)) break;
    result.sizes.push_back(s);
  }
  // Least squares of u = log N against t = log(1/s), over the sizes that see more than one box.
  double st = 0, su = 0, stt = 0, stu = 0;
  for (double s : result.sizes) {
    const int64_t n = count_boxes(mask, box, s);
    result.counts.push_back(n);
    if (n < 2) continue;
    const double t = -std::log(s), u = std::log(double(n));
    st += t, su += u, stt += t * t, stu += t * u;
    ++result.fitted;
  }
  if (result.fitted < 2)
    throw InvalidInput(fmt::format(
        "box counting needs at least two box sizes that see more than one box, between {} and {} pixels (the set "
        "spans {} pixels)",
        options.min_box, max_box, result.extent));
  const double k = double(result.fitted);
  result.dimension = (k * stu - st * su) / (k * stt - st * st);
  return result;
}

}  // namespace tessera
