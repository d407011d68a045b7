#include "tessera/raster2d/scanline.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "tessera/core/parallel.hpp"

namespace tessera {
namespace {

// A path edge oriented top to bottom (y0 < y1); winding is +1 when its contour runs down (y increasing) along it.
struct Edge {
  double x0, y0, x1, y1;
  double dxdy;
  int winding;
};

// The edges of a path that can touch the image, binned into fixed bands of rows (a CSR table: band b owns
// band_edges[band_start[b] .. band_start[b + 1])), with the bounds of what was kept.
struct EdgeTable {
  std::vector<Edge> edges;
  std::vector<int> band_start;
  std::vector<int> band_edges;
  double min_x = HUGE_VAL, max_x = -HUGE_VAL;
};

// The first integer i in [lo, hi] with i + 0.5 >= v (the first pixel center at or after v), clamped to [lo, hi].
int first_center_at_or_after(double v, int lo, int hi) {
  const double c = std::ceil(std::clamp(v, double(lo) - 1.0, double(hi) + 1.0) - 0.5);
  return std::clamp(int(c), lo, hi);
}

// floor(v) clamped to [lo, hi], safe for any finite v.
int clamped_floor(double v, int lo, int hi) {
  return std::clamp(int(std::floor(std::clamp(v, double(lo) - 1.0, double(hi) + 1.0))), lo, hi);
}

bool finite_contour(const std::vector<Vec2>& contour) {
  return std::all_of(contour.begin(), contour.end(),
                     [](const Vec2& p) { return std::isfinite(p.x) && std::isfinite(p.y); });
}

EdgeTable build_edge_table(const Path& path, int width, int height) {
  EdgeTable table;
  for (const auto& contour : path.contours) {
    if (contour.size() < 3 || !finite_contour(contour)) continue;
    for (size_t i = 0; i < contour.size(); ++i) {
      const Vec2& a = contour[i];
      const Vec2& b = contour[(i + 1) % contour.size()];
      if (a.y == b.y) continue;  // horizontal edges meet no scanline and enclose no area
      Edge e = a.y < b.y ? Edge{a.x, a.y, b.x, b.y, 0, +1} : Edge{b.x, b.y, a.x, a.y, 0, -1};
      // Edges above, below or right of the image change no pixel (pixels depend only on crossings left of them).
      if (e.y1 <= 0 || e.y0 >= height) continue;
      const double lo = std::min(e.x0, e.x1), hi = std::max(e.x0, e.x1);
      table.max_x = std::max(table.max_x, hi);  // coverage may extend to the right of a culled edge
      if (lo >= width) continue;
      table.min_x = std::min(table.min_x, lo);
      e.dxdy = (e.x1 - e.x0) / (e.y1 - e.y0);
      table.edges.push_back(e);
    }
  }
  const int bands = (height + kScanBandHeight - 1) / kScanBandHeight;
  table.band_start.assign(size_t(bands) + 1, 0);
  auto band_range = [&](const Edge& e) {
    const int row_lo = clamped_floor(e.y0, 0, height - 1);
    const int row_hi = std::clamp(int(std::ceil(std::min(e.y1, double(height)))) - 1, 0, height - 1);
    return std::pair{row_lo / kScanBandHeight, row_hi / kScanBandHeight};
  };
  for (const Edge& e : table.edges) {
    const auto [b0, b1] = band_range(e);
    for (int b = b0; b <= b1; ++b) ++table.band_start[size_t(b) + 1];
  }
  for (int b = 0; b < bands; ++b) table.band_start[size_t(b) + 1] += table.band_start[size_t(b)];
  table.band_edges.resize(size_t(table.band_start.back()));
  std::vector<int> fill(table.band_start.begin(), table.band_start.end() - 1);
  for (int i = 0; i < int(table.edges.size()); ++i) {
    const auto [b0, b1] = band_range(table.edges[size_t(i)]);
    for (int b = b0; b <= b1; ++b) table.band_edges[size_t(fill[size_t(b)]++)] = i;
  }
  return table;
}

bool inside(FillRule rule, int winding) { return rule == FillRule::non_zero ? winding != 0 : (winding & 1) != 0; }

// ---- Aliased: the notes' edge table and active edge list ----------------------------------------------------------

// The notes step x by dx/dy per scanline. Accumulating that increment drifts (1/3 is not a binary fraction), which
// moves pixel centers lying exactly on an edge to the wrong side; so x is evaluated from the edge's endpoints on every
// scanline instead, x0 + ((y - y0) dx) / dy, which is exact whenever the true intersection is representable.
struct ActiveEdge {
  double x;       // intersection with the current scanline's center line
  double x0, y0;  // upper endpoint
  double dx, dy;  // x1 - x0, y1 - y0 (dy > 0)
  int row_end;    // first row whose center is at or below the edge's lower end
  int winding;

  double x_at(double y) const { return x0 + ((y - y0) * dx) / dy; }
};

void scan_band_aliased(const EdgeTable& table, const int* first, const int* last, int r0, int r1, FillRule rule,
                       int width, const SpanSink& sink) {
  // Edge table: each edge keyed by the first row whose center it reaches, x evaluated at that center.
  std::vector<std::pair<int, ActiveEdge>> pending;
  for (const int* it = first; it != last; ++it) {
    const Edge& e = table.edges[size_t(*it)];
    const int row_begin = first_center_at_or_after(e.y0, r0, r1);
    const int row_end = first_center_at_or_after(e.y1, r0, r1);
    if (row_begin >= row_end) continue;
    pending.push_back({row_begin, ActiveEdge{0, e.x0, e.y0, e.x1 - e.x0, e.y1 - e.y0, row_end, e.winding}});
  }
  std::stable_sort(pending.begin(), pending.end(), [](const auto& a, const auto& b) { return a.first < b.first; });

  std::vector<ActiveEdge> active;
  size_t next = 0;
  for (int y = r0; y < r1 && (next < pending.size() || !active.empty()); ++y) {
    std::erase_if(active, [y](const ActiveEdge& e) { return e.row_end <= y; });
    for (; next < pending.size() && pending[next].first == y; ++next) active.push_back(pending[next].second);
    for (ActiveEdge& e : active) e.x = e.x_at(y + 0.5);
    // Insertion sort: the order barely changes from one scanline to the next.
    for (size_t i = 1; i < active.size(); ++i)
      for (size_t j = i; j > 0 && active[j].x < active[j - 1].x; --j) std::swap(active[j], active[j - 1]);
    int winding = 0;
    double span_start = 0;
    for (const ActiveEdge& e : active) {
      const bool was_in = inside(rule, winding);
      winding += e.winding;
      const bool now_in = inside(rule, winding);
      if (!was_in && now_in) {
        span_start = e.x;
      } else if (was_in && !now_in) {
        const int x0 = first_center_at_or_after(span_start, 0, width);
        const int x1 = first_center_at_or_after(e.x, 0, width);
        if (x0 < x1) sink(y, x0, x1, nullptr);
      }
    }
    if (inside(rule, winding)) {  // the closing edges lie right of the image and were culled
      const int x0 = first_center_at_or_after(span_start, 0, width);
      if (x0 < width) sink(y, x0, width, nullptr);
    }
  }
}

// ---- Antialiased: signed area and cover per cell ------------------------------------------------------------------

// Deposits the segment (x, y0) -> (x_end, y1), y0 < y1, inside the accumulation buffer (x in [0, stride - 2]), with
// sign `dir`: each cell gets the change of the segment's coverage, so a running sum along a row is the area of each
// pixel to the right of the segment, times dir.
void deposit_segment(float* acc, int stride, double x, double y0, double x_end, double y1, double dir) {
  if (!(y1 > y0)) return;
  const double dxdy = (x_end - x) / (y1 - y0);
  const int row_end = int(std::ceil(y1));
  for (int y = int(std::floor(y0)); y < row_end; ++y) {
    float* row = acc + ptrdiff_t(y) * stride;
    const double dy = std::min(y + 1.0, y1) - std::max(double(y), y0);
    const double x_next = y + 1.0 >= y1 ? x_end : x + dxdy * dy;
    const double d = dy * dir;
    const double xl = std::min(x, x_next), xr = std::max(x, x_next);
    const double xl_floor = std::floor(xl), xr_ceil = std::ceil(xr);
    const int il = int(xl_floor), ir = int(xr_ceil);
    if (ir <= il + 1) {  // inside one cell: the trapezoid right of the segment, split between this cell and the next
      const double xmf = 0.5 * (x + x_next) - xl_floor;
      row[il] += float(d - d * xmf);
      row[il + 1] += float(d * xmf);
    } else {  // across cells: a triangle in the first, slabs of width s in between, the rest in the last
      const double s = 1.0 / (xr - xl);
      const double xlf = xl - xl_floor;
      const double a0 = 0.5 * s * (1 - xlf) * (1 - xlf);
      const double xrf = xr - xr_ceil + 1.0;
      const double am = 0.5 * s * xrf * xrf;
      row[il] += float(d * a0);
      if (ir == il + 2) {
        row[il + 1] += float(d * (1 - a0 - am));
      } else {
        const double a1 = s * (1.5 - xlf);
        row[il + 1] += float(d * (a1 - a0));
        for (int xi = il + 2; xi < ir - 1; ++xi) row[xi] += float(d * s);
        const double a2 = a1 + (ir - il - 3) * s;
        row[ir - 1] += float(d * (1 - a2 - am));
      }
      row[ir] += float(d * am);
    }
    x = x_next;
  }
}

// Deposits (xa, ya) -> (xb, yb) clipped to the columns [0, cols]: parts left of 0 (or right of cols) move onto the
// line x = 0 (x = cols), where they still carry their cover to every pixel on their right.
void deposit_clipped(float* acc, int stride, int cols, double xa, double ya, double xb, double yb, double dir) {
  double ts[4] = {0, 0, 0, 1};
  int n = 1;
  for (const double bound : {0.0, double(cols)}) {
    if ((xa < bound) != (xb < bound) && xa != bound && xb != bound) ts[n++] = (bound - xa) / (xb - xa);
  }
  if (n == 3 && ts[2] < ts[1]) std::swap(ts[1], ts[2]);
  ts[n++] = 1;
  auto at = [&](double t, bool is_start, bool is_end) {
    if (is_start) return Vec2(xa, ya);
    if (is_end) return Vec2(xb, yb);
    return Vec2(xa + (xb - xa) * t, ya + (yb - ya) * t);
  };
  for (int i = 0; i + 1 < n; ++i) {
    const Vec2 p = at(ts[i], i == 0, false), q = at(ts[i + 1], false, i + 2 == n);
    deposit_segment(acc, stride, std::clamp(p.x, 0.0, double(cols)), p.y, std::clamp(q.x, 0.0, double(cols)), q.y, dir);
  }
}

float fold_coverage(FillRule rule, float sum) {
  float c = std::fabs(sum);
  if (rule == FillRule::non_zero) {
    c = std::min(c, 1.0f);
  } else {
    c -= 2.0f * std::floor(c * 0.5f);
    if (c > 1.0f) c = 2.0f - c;
  }
  // Snap rounding noise (shared edges cancel up to float error) to exactly empty or full.
  constexpr float kSnap = 1e-4f;
  if (c < kSnap) return 0.0f;
  if (c > 1.0f - kSnap) return 1.0f;
  return c;
}

void scan_band_antialiased(const EdgeTable& table, const int* first, const int* last, int r0, int r1, FillRule rule,
                           int width, const SpanSink& sink) {
  const int bx0 = clamped_floor(table.min_x, 0, width);
  const int bx1 = std::clamp(int(std::ceil(std::clamp(table.max_x, -1.0, width + 1.0))), 0, width);
  if (bx0 >= bx1) return;
  const int cols = bx1 - bx0, stride = cols + 2, rows = r1 - r0;
  std::vector<float> acc(size_t(stride) * size_t(rows), 0.0f);
  for (const int* it = first; it != last; ++it) {
    const Edge& e = table.edges[size_t(*it)];
    const double ya = std::max(e.y0, double(r0)), yb = std::min(e.y1, double(r1));
    if (!(ya < yb)) continue;
    const double xa = ya == e.y0 ? e.x0 : e.x0 + (ya - e.y0) * e.dxdy;
    const double xb = yb == e.y1 ? e.x1 : e.x0 + (yb - e.y0) * e.dxdy;
    deposit_clipped(acc.data(), stride, cols, xa - bx0, ya - r0, xb - bx0, yb - r0, e.winding);
  }
  std::vector<float> coverage(size_t(cols), 0.0f);
  for (int r = 0; r < rows; ++r) {
    const float* row = acc.data() + size_t(r) * size_t(stride);
    float sum = 0;
    for (int i = 0; i < cols; ++i) {
      sum += row[i];
      coverage[size_t(i)] = fold_coverage(rule, sum);
    }
    for (int i = 0; i < cols;) {
      if (coverage[size_t(i)] == 0.0f) {
        ++i;
        continue;
      }
      int j = i;
      bool full = true;
      for (; j < cols && coverage[size_t(j)] != 0.0f; ++j) full = full && coverage[size_t(j)] == 1.0f;
      sink(r0 + r, bx0 + i, bx0 + j, full ? nullptr : coverage.data() + i);
      i = j;
    }
  }
}

}  // namespace

void scan_path(const Path& path, FillRule rule, int width, int height, bool antialias, const SpanSink& sink) {
  if (width <= 0 || height <= 0) return;
  const EdgeTable table = build_edge_table(path, width, height);
  if (table.edges.empty()) return;
  const int bands = int(table.band_start.size()) - 1;
  int band_lo = bands, band_hi = 0;
  for (int b = 0; b < bands; ++b) {
    if (table.band_start[size_t(b)] == table.band_start[size_t(b) + 1]) continue;
    band_lo = std::min(band_lo, b);
    band_hi = b + 1;
  }
  auto scan_band = [&](int b) {
    const int* first = table.band_edges.data() + table.band_start[size_t(b)];
    const int* last = table.band_edges.data() + table.band_start[size_t(b) + 1];
    const int r0 = b * kScanBandHeight, r1 = std::min(height, r0 + kScanBandHeight);
    if (antialias)
      scan_band_antialiased(table, first, last, r0, r1, rule, width, sink);
    else
      scan_band_aliased(table, first, last, r0, r1, rule, width, sink);
  };
  if (band_hi - band_lo <= 1) {
    for (int b = band_lo; b < band_hi; ++b) scan_band(b);
    return;
  }
  parallel_for(band_lo, band_hi, 1, [&](int64_t b0, int64_t b1) {
    for (int64_t b = b0; b < b1; ++b) scan_band(int(b));
  });
}

}  // namespace tessera
