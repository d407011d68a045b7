#include "tessera/fractal/dimension.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "tessera/core/error.hpp"

namespace tessera {
namespace {

int64_t count_boxes(const Image<uint8_t>& mask, int s) {
  const int bw = (mask.width() + s - 1) / s, bh = (mask.height() + s - 1) / s;
  std::vector<uint8_t> hit(size_t(bw) * size_t(bh), 0);
  for (int y = 0; y < mask.height(); ++y) {
    const uint8_t* row = mask.row(y);
    uint8_t* boxes = hit.data() + size_t(y / s) * size_t(bw);
    for (int x = 0; x < mask.width(); ++x) boxes[x / s] |= uint8_t(row[x] != 0);
  }
  return std::count(hit.begin(), hit.end(), uint8_t(1));
}

}  // namespace

BoxCountResult box_counting_dimension(const Image<uint8_t>& mask, const BoxCountOptions& options) {
  if (options.min_box < 1) throw InvalidInput(fmt::format("smallest box must be >= 1 pixel, got {}", options.min_box));
  if (!(options.factor > 1)) throw InvalidInput(fmt::format("box size factor must be > 1, got {}", options.factor));
  if (std::none_of(mask.pixels().begin(), mask.pixels().end(), [](uint8_t v) { return v != 0; }))
    throw InvalidInput("box counting needs at least one set pixel, the image is empty");
  const int max_box =
      options.max_box > 0 ? options.max_box : std::max(options.min_box, std::min(mask.width(), mask.height()) / 4);
  BoxCountResult result;
  for (double s = options.min_box; s <= max_box + 1e-9; s *= options.factor) {
    const int size = int(std::lround(s));
    if (result.sizes.empty() || size != result.sizes.back()) result.sizes.push_back(size);
  }
  if (result.sizes.size() < 2)
    throw InvalidInput(
        fmt::format("box counting needs at least two box sizes between {} and {} pixels", options.min_box, max_box));
  // Least squares of u = log N against t = log(1/s).
  double st = 0, su = 0, stt = 0, stu = 0;
  for (int s : result.sizes) {
    const int64_t n = count_boxes(mask, s);
    result.counts.push_back(n);
    const double t = -std::log(double(s)), u = std::log(double(n));
    st += t, su += u, stt += t * t, stu += t * u;
  }
  const double k = double(result.sizes.size());
  result.dimension = (k * stu - st * su) / (k * stt - st * st);
  return result;
}

}  // namespace tessera
