// Transfer functions: points, presets on the object's scale of a value profile (Otsu's threshold), and the JSON
// and CSV files of `--tf`.
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <tuple>

#include "tessera/core/atomic_file.hpp"
#include "tessera/core/parse.hpp"
#include "tessera/volume/volume_render.hpp"

namespace tessera {

TransferFunction::TransferFunction(std::vector<Point> points) : points_(std::move(points)) {
  if (points_.empty()) throw InvalidInput("a transfer function needs at least one point");
  for (const auto& p : points_) {
    if (!std::isfinite(p.value)) throw InvalidInput(fmt::format("point value {} is not finite", p.value));
    for (int k = 0; k < 3; ++k)
      if (!(p.color[k] >= 0 && p.color[k] <= kMaxColor))
        throw InvalidInput(fmt::format("color component {} is outside [0, {}]", p.color[k], kMaxColor));
    if (!(p.opacity >= 0 && p.opacity <= 1)) throw InvalidInput(fmt::format("opacity {} is outside [0, 1]", p.opacity));
  }
  std::stable_sort(points_.begin(), points_.end(), [](const Point& a, const Point& b) { return a.value < b.value; });
}

Vec4f TransferFunction::operator()(float v) const {
  if (points_.empty()) return Vec4f(0.0f);
  if (v <= points_.front().value) return Vec4f(points_.front().color, points_.front().opacity);
  if (v >= points_.back().value) return Vec4f(points_.back().color, points_.back().opacity);
  const auto hi =
      std::upper_bound(points_.begin(), points_.end(), v, [](float x, const Point& p) { return x < p.value; });
  const auto lo = hi - 1;
  // In double: the difference of two finite floats can overflow a float (values of both signs near its limit).
  const float t = float((double(v) - lo->value) / (double(hi->value) - lo->value));
  return Vec4f(glm::mix(lo->color, hi->color, t), lo->opacity + t * (hi->opacity - lo->opacity));
}

float TransferFunction::max_opacity(float lo, float hi) const {
  float m = std::max((*this)(lo).w, (*this)(hi).w);
  for (const auto& p : points_)
    if (p.value >= lo && p.value <= hi) m = std::max(m, p.opacity);
  return m;
}

ValueProfile profile_values(const Volume<float>& volume) {
  if (volume.empty()) throw InvalidInput("cannot profile an empty volume");
  ValueProfile p;
  std::tie(p.lo, p.hi) = value_range(volume);
  p.diagonal = glm::length(volume.to_world(Vec3(volume.dims() - 1)) - volume.origin());
  p.threshold = p.median = p.top = p.hi;
  if (!(p.hi > p.lo)) return p;
  // Otsu's histogram spans [lo, the 99th percentile], values above counting in its last bin: the long tail of a
  // skewed field, such as the metaballs' centres, would otherwise squeeze the rest into one bin. Percentiles are
  // numpy's "lower" ones (the element at floor(f (n - 1)) in sorted order), found by selection in a copy.
  std::vector<float> values(volume.voxels().begin(), volume.voxels().end());
  const auto percentile = [](std::vector<float>::iterator first, std::vector<float>::iterator last, double f) {
    const auto at = first + std::ptrdiff_t(f * double(last - first - 1));
    std::nth_element(first, at, last);
    return double(*at);
  };
  const double p99 = percentile(values.begin(), values.end(), 0.99);
  const double span_hi = p99 > p.lo ? p99 : p.hi;
  constexpr int kBins = 1024;
  const std::vector<uint64_t> counts = histogram(volume, kBins, p.lo, span_hi);
  // Otsu's method: the split of the histogram that maximizes the between-class variance w0 w1 (m0 - m1)^2.
  double total = 0, total_moment = 0;
  for (int b = 0; b < kBins; ++b) {
    total += double(counts[size_t(b)]);
    total_moment += double(b) * double(counts[size_t(b)]);
  }
  double w0 = 0, moment0 = 0, best = -1;
  int split = 0;  // the last bin of the background
  for (int b = 0; b + 1 < kBins; ++b) {
    w0 += double(counts[size_t(b)]);
    moment0 += double(b) * double(counts[size_t(b)]);
    const double w1 = total - w0;
    if (w0 == 0 || w1 == 0) continue;
    const double d = moment0 / w0 - (total_moment - moment0) / w1;
    const double variance = w0 * w1 * d * d;
    if (variance > best) best = variance, split = b;
  }
  p.threshold = p.lo + (split + 1) * (span_hi - p.lo) / kBins;
  // The object's median and top (99.5th percentile) among the values above the threshold.
  const auto object = std::partition(values.begin(), values.end(), [&](float x) { return !(x > p.threshold); });
  if (object != values.end()) {
    p.median = percentile(object, values.end(), 0.5);
    p.top = percentile(object, values.end(), 0.995);
  }
  return p;
}

namespace {

/// A control point on the object's scale of a profile: position s (ValueProfile::value_at), color, and opacity per
/// kReferenceDiagonal-th of the diagonal.
struct ScalePoint {
  double s;
  Vec3f color;
  double opacity;
};

/// The transfer function of scale points on a volume of profile `p`.
TransferFunction on_scale(const std::vector<ScalePoint>& points, const ValueProfile& p) {
  // Opacity per reference length -> per world unit: 1 - (1 - a)^(kReferenceDiagonal / diagonal).
  const double exponent = TransferFunction::kReferenceDiagonal / std::max(p.diagonal, 1e-30);
  std::vector<TransferFunction::Point> out;
  for (const auto& q : points)
    out.push_back(
        {float(p.value_at(q.s)), q.color, float(std::clamp(1 - std::pow(1 - q.opacity, exponent), 0.0, 1.0))});
  return TransferFunction(std::move(out));
}

/// The presets on the object's scale. They were made for headsq (CT, 12-bit: threshold 644.8, top 2529) and the
/// clinical MRI head of the shared data (8-bit: 62.2, 255), where they give the values of the ramps first written for
/// them (bone from 1000 over 1150 to 2000, skin from 400 to 600 and 1100 to 1300, MRI from 40 to 90 and 255).
const std::vector<std::pair<std::string, std::vector<ScalePoint>>>& preset_table() {
  static const std::vector<std::pair<std::string, std::vector<ScalePoint>>> table = {
      {"ct-bone", {{0.19, {0.9f, 0.6f, 0.4f}, 0}, {0.27, {0.95f, 0.9f, 0.8f}, 0.6}, {0.72, {1, 1, 0.95f}, 0.9}}},
      {"ct-skin",
       {{-0.13, {0.8f, 0.5f, 0.4f}, 0},
        {-0.02, {0.9f, 0.7f, 0.6f}, 0.15},
        {0.24, {0.9f, 0.7f, 0.6f}, 0.15},
        {0.35, {1, 1, 0.95f}, 0.8}}},
      {"mri", {{-0.12, {0.5f, 0.3f, 0.3f}, 0}, {0.14, {0.9f, 0.75f, 0.6f}, 0.1}, {1.0, {1, 1, 1}, 0.5}}},
  };
  return table;
}

}  // namespace

const std::vector<std::string>& TransferFunction::preset_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const auto& [name, points] : preset_table()) n.push_back(name);
    return n;
  }();
  return names;
}

TransferFunction TransferFunction::preset(const std::string& name, const ValueProfile& profile) {
  for (const auto& [key, points] : preset_table()) {
    if (key != name) continue;
    if (!profile.separable())
      throw InvalidInput(
          fmt::format("preset '{}' cannot apply: every voxel has the value {}, so there is no tissue to "
                      "tell from the background (use --tf or the default transfer function)",
                      name, profile.lo));
    return on_scale(points, profile);
  }
  throw InvalidInput(fmt::format("unknown transfer-function preset '{}' ({})", name, fmt::join(preset_names(), ", ")));
}

TransferFunction TransferFunction::automatic(const ValueProfile& profile) {
  if (!profile.separable())  // a constant volume: its box as a light haze
    return on_scale({{0, {0.9f, 0.8f, 0.7f}, 0.02}}, profile);
  // On the object's scale, with its median in the middle of the ramp: skewed fields keep most of their object
  // translucent instead of crowding it into the ramp's first steps.
  const double median = (profile.median - profile.threshold) / (profile.top - profile.threshold);
  return on_scale({{0, {0.8f, 0.35f, 0.2f}, 0}, {median, {0.95f, 0.7f, 0.45f}, 0.05}, {1, {1, 0.97f, 0.92f}, 0.3}},
                  profile);
}

namespace {

/// A point from its five numbers (value, r, g, b, opacity) as parsed, refusing a value beyond float's range (its
/// conversion would be undefined) with a message naming `where`; the constructor checks the rest.
TransferFunction::Point point_of(const double (&v)[5], const std::string& where) {
  for (int k = 0; k < 5; ++k)
    if (!(std::fabs(v[k]) <= std::numeric_limits<float>::max()))
      throw InvalidInput(fmt::format("{}: {} does not fit a float", where, v[k]));
  return {float(v[0]), {float(v[1]), float(v[2]), float(v[3])}, float(v[4])};
}

}  // namespace

TransferFunction TransferFunction::from_json(const std::string& text, const std::string& name) {
  try {
    const auto j = nlohmann::json::parse(text);
    std::vector<Point> points;
    for (const auto& p : j.at("points")) {
      if (!p.is_array() || p.size() != 5)
        throw InvalidInput(fmt::format("{}: each point is [value, r, g, b, opacity]", name));
      const double v[5] = {p[0].get<double>(), p[1].get<double>(), p[2].get<double>(), p[3].get<double>(),
                           p[4].get<double>()};
      points.push_back(point_of(v, name));
    }
    return TransferFunction(std::move(points));
  } catch (const nlohmann::json::exception& e) {
    throw InvalidInput(fmt::format("{}: {}", name, e.what()));
  }
}

TransferFunction TransferFunction::from_csv(const std::string& text, const std::string& name) {
  std::vector<Point> points;
  std::istringstream in(text);
  long line_no = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    const auto t = trim(line);
    if (t.empty() || t[0] == '#') continue;
    const std::string where = at_line(name, line_no);
    const auto v = parse_doubles(t, 5, where);
    points.push_back(point_of({v[0], v[1], v[2], v[3], v[4]}, where));
  }
  return TransferFunction(std::move(points));
}

TransferFunction TransferFunction::load(const std::filesystem::path& path) {
  const std::string text = read_file(path);
  return path.extension() == ".json" ? from_json(text, path.string()) : from_csv(text, path.string());
}

}  // namespace tessera
