#include "color_quantize.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "tessera/core/error.hpp"

namespace tessera::detail {
namespace {

Rgb8 unpack(uint32_t v) { return Rgb8(uint8_t(v >> 16), uint8_t(v >> 8), uint8_t(v)); }

/// Dithering passes on a pixel's error shortened to at most sqrt(kDitherLimit * m) (and at least kDitherFloor) levels,
/// m the frame's mean squared error without dithering: errors over a fixed share of how far the palette is from the
/// frame are damped, as libimagequant damps errors over 2.4 times its palette's error. Undamped, the error toward a
/// color the palette lacks grows until a far color is chosen: specks up to 155 levels off on a 640x360 gradient.
/// Measured there (per-pixel max error, mean error after a 5x5 box blur, in levels): undamped 155, 1.34; factor 4
/// 40, 1.34; 8 49, 1.30; 16 76, 1.29; without dithering 33, 4.16. A sparse palette (black and white for a gray) has
/// a large m and keeps its full error, so the local average stays right.
constexpr float kDitherLimit = 8;
constexpr float kDitherFloor = 16;

/// Bits per channel of the mapper's cells (16^3 cells of 16^3 colors). Encoding 640x360 gradient frames, a new palette
/// each, CPU ms per frame without/with dithering: 5 bits 18-21/32 (building cells dominated), 4 bits 14/24, 3 bits
/// 14/24-27 (long candidate lists).
constexpr int kCellBits = 4;

/// The 5-bit-per-channel histogram cell of a color.
int bin_of(int r, int g, int b) { return (r >> 3) << 10 | (g >> 3) << 5 | (b >> 3); }

/// One non-empty histogram cell: its pixel count and the sums of its pixels' channels.
struct Bin {
  double count = 0;
  std::array<double, 3> sum{};
  double mean(int axis) const { return sum[size_t(axis)] / count; }
};

/// A box of median cut: bins [begin, end) of the bin list, and its squared error (bins at their means).
struct Box {
  size_t begin, end;
  double error;
};

/// Sum over the three axes of sum(c x^2) - (sum c x)^2 / sum c: the squared error of bins at their means around
/// the box's mean, from running sums.
struct Moments {
  double count = 0;
  std::array<double, 3> sum{}, sum2{};
  void add(const Bin& b) {
    count += b.count;
    for (int a = 0; a < 3; ++a) {
      sum[size_t(a)] += b.sum[size_t(a)];
      sum2[size_t(a)] += b.sum[size_t(a)] * b.mean(a);
    }
  }
  double error() const {
    if (count <= 0) return 0;
    double e = 0;
    for (int a = 0; a < 3; ++a) e += sum2[size_t(a)] - sum[size_t(a)] * sum[size_t(a)] / count;
    return std::max(0.0, e);
  }
  double variance(int axis) const {
    return sum2[size_t(axis)] / count - (sum[size_t(axis)] / count) * (sum[size_t(axis)] / count);
  }
};

Moments moments_of(const std::vector<Bin>& bins, const Box& box) {
  Moments m;
  for (size_t i = box.begin; i < box.end; ++i) m.add(bins[i]);
  return m;
}

/// Splits `box` in two: bins sorted along the axis of largest variance, cut where the halves' summed squared error is
/// smallest. Returns the cut index.
size_t split(std::vector<Bin>& bins, const Box& box) {
  const Moments whole = moments_of(bins, box);
  int axis = 0;
  for (int a = 1; a < 3; ++a)
    if (whole.variance(a) > whole.variance(axis)) axis = a;
  std::sort(bins.begin() + ptrdiff_t(box.begin), bins.begin() + ptrdiff_t(box.end),
            [axis](const Bin& a, const Bin& b) { return a.mean(axis) < b.mean(axis); });
  Moments left;
  size_t best = box.begin + 1;
  double best_error = INFINITY;
  for (size_t cut = box.begin + 1; cut < box.end; ++cut) {
    left.add(bins[cut - 1]);
    Moments right;
    right.count = whole.count - left.count;
    for (size_t a = 0; a < 3; ++a) {
      right.sum[a] = whole.sum[a] - left.sum[a];
      right.sum2[a] = whole.sum2[a] - left.sum2[a];
    }
    const double e = left.error() + right.error();
    if (e < best_error) best_error = e, best = cut;
  }
  return best;
}

void check_palette_size(long long colors) {
  if (colors < 1 || colors > 256) throw InvalidInput(fmt::format("a palette holds 1 to 256 colors, not {}", colors));
}

Rgb8 mean_color(const Moments& m) {
  return Rgb8(uint8_t(std::lround(m.sum[0] / m.count)), uint8_t(std::lround(m.sum[1] / m.count)),
              uint8_t(std::lround(m.sum[2] / m.count)));
}

}  // namespace

std::optional<std::vector<Rgb8>> distinct_colors(std::span<const Rgb8> pixels, int limit) {
  // Open addressing over 4x the limit's slots; 0xFFFFFFFF (not a 24-bit color) marks an empty slot.
  size_t slots = 16;
  while (slots < size_t(std::max(limit, 1)) * 4) slots *= 2;
  std::vector<uint32_t> table(slots, 0xFFFFFFFFu);
  std::vector<uint32_t> found;
  uint32_t last = 0xFFFFFFFFu;
  for (const Rgb8& p : pixels) {
    const uint32_t v = pack_rgb(p);
    if (v == last) continue;
    last = v;
    size_t i = size_t(uint32_t(v * 2654435761u)) & (slots - 1);  // Knuth's multiplicative hash
    while (table[i] != 0xFFFFFFFFu && table[i] != v) i = (i + 1) & (slots - 1);
    if (table[i] == v) continue;
    if (int(found.size()) == limit) return std::nullopt;
    table[i] = v;
    found.push_back(v);
  }
  std::sort(found.begin(), found.end());
  std::vector<Rgb8> colors;
  colors.reserve(found.size());
  for (uint32_t v : found) colors.push_back(unpack(v));
  return colors;
}

std::vector<Rgb8> quantize_palette(std::span<const Rgb8> pixels, int max_colors) {
  check_palette_size(max_colors);
  if (auto exact = distinct_colors(pixels, max_colors)) return *exact;
  return median_cut_palette(pixels, max_colors);
}

std::vector<Rgb8> median_cut_palette(std::span<const Rgb8> pixels, int max_colors) {
  check_palette_size(max_colors);
  std::vector<Bin> histogram(size_t(1) << 15);
  for (const Rgb8& p : pixels) {
    Bin& b = histogram[size_t(bin_of(p.x, p.y, p.z))];
    b.count += 1;
    b.sum[0] += p.x, b.sum[1] += p.y, b.sum[2] += p.z;
  }
  std::vector<Bin> bins;
  for (const Bin& b : histogram)
    if (b.count > 0) bins.push_back(b);

  std::vector<Box> boxes{{0, bins.size(), moments_of(bins, {0, bins.size(), 0}).error()}};
  while (int(boxes.size()) < max_colors) {
    // The box with the largest squared error that can still be split.
    size_t pick = boxes.size();
    for (size_t i = 0; i < boxes.size(); ++i)
      if (boxes[i].end - boxes[i].begin >= 2 && (pick == boxes.size() || boxes[i].error > boxes[pick].error)) pick = i;
    if (pick == boxes.size()) break;
    const Box box = boxes[pick];
    const size_t cut = split(bins, box);
    const Box low{box.begin, cut, 0}, high{cut, box.end, 0};
    boxes[pick] = {low.begin, low.end, moments_of(bins, low).error()};
    boxes.push_back({high.begin, high.end, moments_of(bins, high).error()});
  }

  std::vector<Rgb8> palette;
  palette.reserve(boxes.size());
  for (const Box& box : boxes) {
    const Moments m = moments_of(bins, box);
    palette.push_back(mean_color(m));
  }
  return palette;
}

PaletteMapper::PaletteMapper(std::vector<Rgb8> palette)
    : palette_(std::move(palette)),
      cell_start_(size_t(1) << (3 * kCellBits), -1),
      cell_count_(size_t(1) << (3 * kCellBits), 0) {
  check_palette_size(ptrdiff_t(palette_.size()));
}

uint8_t PaletteMapper::nearest(int r, int g, int b) {
  constexpr int kShift = 8 - kCellBits;
  const int cell = (r >> kShift) << (2 * kCellBits) | (g >> kShift) << kCellBits | (b >> kShift);
  if (cell_start_[size_t(cell)] < 0) build_cell(cell);
  const Candidate* list = candidates_.data() + cell_start_[size_t(cell)];
  const Candidate* end = list + cell_count_[size_t(cell)];
  uint8_t best = list->index;
  int best_d = INT32_MAX;
  // Candidates come nearest cell first: none after one whose distance to the cell exceeds the best can win.
  for (; list != end && list->cell_distance <= best_d; ++list) {
    const int dr = r - list->color.x, dg = g - list->color.y, db = b - list->color.z;
    const int d = dr * dr + dg * dg + db * db;
    if (d < best_d || (d == best_d && list->index < best)) best_d = d, best = list->index;
  }
  return best;
}

void PaletteMapper::build_cell(int cell) {
  // Candidates of the cell [lo, lo + kSize - 1]^3: entries no farther from the cell than the nearest farthest corner.
  constexpr int kSize = 1 << (8 - kCellBits), kMask = (1 << kCellBits) - 1;
  const int lo[3] = {(cell >> (2 * kCellBits)) * kSize, ((cell >> kCellBits) & kMask) * kSize, (cell & kMask) * kSize};
  std::array<int, 256> near;
  int threshold = INT32_MAX;
  for (size_t i = 0; i < palette_.size(); ++i) {
    int n = 0, f = 0;
    for (int a = 0; a < 3; ++a) {
      const int c = palette_[i][a], l = lo[a], h = lo[a] + kSize - 1;
      const int below = c < l ? l - c : (c > h ? c - h : 0);
      const int farthest = std::max(c - l, h - c);
      n += below * below;
      f += farthest * farthest;
    }
    near[i] = n;
    threshold = std::min(threshold, f);
  }
  const size_t start = candidates_.size();
  for (size_t i = 0; i < palette_.size(); ++i)
    if (near[i] <= threshold) candidates_.push_back({near[i], palette_[i], uint8_t(i)});
  std::sort(candidates_.begin() + ptrdiff_t(start), candidates_.end(), [](const Candidate& a, const Candidate& b) {
    return a.cell_distance < b.cell_distance || (a.cell_distance == b.cell_distance && a.index < b.index);
  });
  cell_start_[size_t(cell)] = int32_t(start);
  cell_count_[size_t(cell)] = uint16_t(candidates_.size() - start);
}

/// The mean squared distance from the pixels to their nearest palette colors, from every 7th pixel (so that every
/// column and row is sampled).
float mean_squared_error(std::span<const Rgb8> pixels, PaletteMapper& mapper) {
  double sum = 0;
  size_t n = 0;
  for (size_t i = 0; i < pixels.size(); i += 7, ++n) {
    const Rgb8 p = pixels[i], q = mapper.palette()[mapper.nearest(p.x, p.y, p.z)];
    const glm::vec3 d = glm::vec3(p) - glm::vec3(q);
    sum += double(glm::dot(d, d));
  }
  return n > 0 ? float(sum / double(n)) : 0.f;
}

void map_to_palette(std::span<const Rgb8> pixels, int width, int height, PaletteMapper& mapper, bool dither,
                    std::span<uint8_t> out) {
  TESSERA_CHECK(pixels.size() == size_t(width) * size_t(height) && out.size() == pixels.size());
  if (!dither) {
    uint32_t last = 0xFFFFFFFFu;
    uint8_t last_index = 0;
    for (size_t i = 0; i < pixels.size(); ++i) {
      const uint32_t v = pack_rgb(pixels[i]);
      if (v != last) last = v, last_index = mapper.nearest(pixels[i].x, pixels[i].y, pixels[i].z);
      out[i] = last_index;
    }
    return;
  }
  const float limit2 = std::max(kDitherLimit * mean_squared_error(pixels, mapper), kDitherFloor * kDitherFloor);
  // Errors of this row and the next, one pixel of margin on each side.
  std::vector<glm::vec3> row(size_t(width) + 2), below(size_t(width) + 2);
  const std::vector<Rgb8>& palette = mapper.palette();
  for (int y = 0; y < height; ++y) {
    const bool forward = y % 2 == 0;  // serpentine: even rows left to right, odd rows right to left
    const int step = forward ? 1 : -1;
    std::fill(below.begin(), below.end(), glm::vec3(0));
    for (int k = 0; k < width; ++k) {
      const int x = forward ? k : width - 1 - k;
      const size_t i = size_t(y) * size_t(width) + size_t(x), e = size_t(x) + 1;
      const glm::vec3 v = glm::clamp(glm::vec3(pixels[i]) + row[e], 0.f, 255.f);
      const glm::ivec3 q(v + 0.5f);  // v >= 0, so truncation rounds to nearest
      const uint8_t index = mapper.nearest(q.x, q.y, q.z);
      out[i] = index;
      glm::vec3 error = v - glm::vec3(palette[index]);
      const float length2 = glm::dot(error, error);
      if (length2 > limit2) error *= std::sqrt(limit2 / length2);
      row[size_t(ptrdiff_t(e) + step)] += error * (7.f / 16.f);
      below[size_t(ptrdiff_t(e) - step)] += error * (3.f / 16.f);
      below[e] += error * (5.f / 16.f);
      below[size_t(ptrdiff_t(e) + step)] += error * (1.f / 16.f);
    }
    std::swap(row, below);
  }
}

}  // namespace tessera::detail
