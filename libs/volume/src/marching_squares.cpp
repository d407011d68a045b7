#include "tessera/volume/marching_squares.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <unordered_map>

#include "tessera/core/atomic_file.hpp"
#include "tessera/core/memory_budget.hpp"
#include "tessera/volume/marching_cubes.hpp"

namespace tessera {

std::vector<Polyline> marching_squares(const DepthImage& field, float iso) {
  const int w = field.width(), h = field.height();
  // Edge ids: horizontal edge (x, y)-(x+1, y) is 2 (y w + x), vertical edge (x, y)-(x, y+1) is 2 (y w + x) + 1.
  const auto edge_point = [&](int64_t id) {
    const int64_t cell = id / 2;
    const int x = int(cell % w), y = int(cell / w);
    const int x1 = id % 2 ? x : x + 1, y1 = id % 2 ? y + 1 : y;
    const double a = field(x, y), b = field(x1, y1);
    const double t = std::clamp((double(iso) - a) / (b - a), kEdgeNudge, 1.0 - kEdgeNudge);
    return Vec2(x + t * (x1 - x), y + t * (y1 - y));
  };
  // Visits every cell's segments as (edge from, edge to), oriented with the inside on their left.
  const auto for_each_segment = [&](auto&& add_segment) {
    for (int y = 0; y + 1 < h; ++y)
      for (int x = 0; x + 1 < w; ++x) {
        // Corners counterclockwise in the field's (x right, y down) plane: 0 (x,y), 1 (x+1,y), 2 (x+1,y+1), 3 (x,y+1).
        const float v[4] = {field(x, y), field(x + 1, y), field(x + 1, y + 1), field(x, y + 1)};
        int c = 0;
        for (int k = 0; k < 4; ++k) c |= int(v[k] >= iso) << k;
        if (c == 0 || c == 15) continue;
        const int64_t e[4] = {2 * (int64_t(y) * w + x), 2 * (int64_t(y) * w + x + 1) + 1, 2 * (int64_t(y + 1) * w + x),
                              2 * (int64_t(y) * w + x) + 1};  // edges 0-1, 1-2, 2-3, 3-0
        const auto add = [&](int from, int to) { add_segment(e[from], e[to]); };
        const bool center_inside = (v[0] + v[1] + v[2] + v[3]) / 4 >= iso;
        if (c == 5) {  // saddle, corners 0 and 2 inside: joined cuts off corners 1 and 3, separated cuts off 0 and 2
          center_inside ? (add(0, 1), add(2, 3)) : (add(0, 3), add(2, 1));
          continue;
        }
        if (c == 10) {  // saddle, corners 1 and 3 inside
          center_inside ? (add(3, 0), add(1, 2)) : (add(1, 0), add(3, 2));
          continue;
        }
        // One run of inside corners: the segment goes from the edge leaving the run to the edge entering it.
        int enter = -1, leave = -1;
        for (int k = 0; k < 4; ++k) {
          const bool a = (c >> k) & 1, b = (c >> ((k + 1) % 4)) & 1;
          if (a && !b) leave = k;
          if (!a && b) enter = k;
        }
        add(leave, enter);
      }
  };
  // The segments are counted first, and the memory they need checked before any is stored: per segment its entries
  // in the three hash maps below (about 40 bytes each: a node and a bucket), a point (16), its start (8), and about
  // 60 bytes for what the caller draws or writes (an SVG's text, doubled while it grows), 200 bytes in all.
  constexpr uint64_t kBytesPerSegment = 200;
  uint64_t segments = 0;
  for_each_segment([&](int64_t, int64_t) { ++segments; });
  MemoryBudget::check(saturating_product({segments, kBytesPerSegment}),
                      fmt::format("marching squares: {} contour segments of a {}x{} field", segments, w, h));
  std::unordered_map<int64_t, int64_t> next, prev;
  next.reserve(size_t(segments));
  prev.reserve(size_t(segments));
  for_each_segment([&](int64_t from, int64_t to) {
    next[from] = to;
    prev[to] = from;
  });
  std::vector<Polyline> lines;
  std::unordered_map<int64_t, bool> used;
  used.reserve(size_t(segments));
  const auto trace = [&](int64_t start) {
    Polyline line;
    int64_t e = start;
    while (!used[e]) {
      used[e] = true;
      line.points.push_back(edge_point(e));
      const auto it = next.find(e);
      if (it == next.end()) return line;
      e = it->second;
    }
    line.closed = e == start;
    return line;
  };
  std::vector<int64_t> starts;
  for (const auto& [from, to] : next) starts.push_back(from);
  std::sort(starts.begin(), starts.end());
  for (int64_t s : starts)  // open lines start where no segment ends
    if (!prev.count(s) && !used[s]) lines.push_back(trace(s));
  for (int64_t s : starts)
    if (!used[s]) lines.push_back(trace(s));
  return lines;
}

void write_contours_svg(const std::filesystem::path& path, const std::vector<Polyline>& contours, int width, int height,
                        double scale) {
  std::string svg = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{}\" height=\"{}\" viewBox=\"0 0 {} {}\">\n"
      "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n",
      width * scale, height * scale, width * scale, height * scale);
  for (const auto& line : contours) {
    svg += line.closed ? "<polygon" : "<polyline";
    svg += " fill=\"none\" stroke=\"#1f4e9a\" stroke-width=\"1.5\" points=\"";
    for (const auto& p : line.points) svg += fmt::format("{:.3f},{:.3f} ", (p.x + 0.5) * scale, (p.y + 0.5) * scale);
    svg += "\"/>\n";
  }
  svg += "</svg>\n";
  write_file_atomic(path, svg);
}

}  // namespace tessera
