#include "tessera/color/model.hpp"

#include <fmt/format.h>

#include "rows.hpp"
#include "tessera/color/color.hpp"
#include "tessera/color/srgb.hpp"
#include "tessera/core/error.hpp"
#include "tessera/core/parallel.hpp"
#include "tessera/core/parse.hpp"

namespace tessera {
namespace {

// Each model as a name, a component count and its two conversions to and from the hub, linear RGB.
struct ModelInfo {
  std::string_view name;
  int components;
  int hue;
  Vec3 (*to_rgb)(const Vec4&);
  Vec4 (*from_rgb)(const Vec3&);
};

// Adapts a Vec3 -> Vec3 conversion to the table's Vec4 signatures.
template <Vec3 (*F)(const Vec3&)>
Vec3 to_rgb3(const Vec4& v) {
  return F(Vec3(v));
}
template <Vec3 (*F)(const Vec3&)>
Vec4 from_rgb3(const Vec3& rgb) {
  return Vec4(F(rgb), 0.0);
}
Vec3 identity(const Vec3& v) { return v; }
Vec3 encode(const Vec3& v) { return srgb_encode(v); }
Vec3 decode(const Vec3& v) { return srgb_decode(v); }

// In the order of the ColorModel enum.
constexpr std::array<ModelInfo, 9> kModels = {{
    {"rgb", 3, -1, to_rgb3<identity>, from_rgb3<identity>},
    {"cmy", 3, -1, to_rgb3<cmy_to_rgb>, from_rgb3<rgb_to_cmy>},
    {"cmyk", 4, -1, cmyk_to_rgb, rgb_to_cmyk},
    {"hsv", 3, 0, to_rgb3<hsv_to_rgb>, from_rgb3<rgb_to_hsv>},
    {"hls", 3, 0, to_rgb3<hls_to_rgb>, from_rgb3<rgb_to_hls>},
    {"yiq", 3, -1, to_rgb3<yiq_to_rgb>, from_rgb3<rgb_to_yiq>},
    {"xyz", 3, -1, to_rgb3<xyz_to_rgb>, from_rgb3<rgb_to_xyz>},
    {"xyy", 3, -1, to_rgb3<xyy_to_rgb>, from_rgb3<rgb_to_xyy>},
    {"srgb", 3, -1, to_rgb3<decode>, from_rgb3<encode>},
}};

const ModelInfo& info(ColorModel model) { return kModels[size_t(model)]; }

std::string model_list() {
  std::string list;
  for (const ModelInfo& m : kModels) list += (list.empty() ? "" : ", ") + std::string(m.name);
  return list;
}

}  // namespace

std::string_view model_name(ColorModel model) { return info(model).name; }

ColorModel parse_color_model(std::string_view name) {
  for (ColorModel m : kColorModels)
    if (info(m).name == name) return m;
  throw InvalidInput(fmt::format("unknown color model '{}' (expected one of {})", printable(name), model_list()));
}

int component_count(ColorModel model) { return info(model).components; }

int hue_index(ColorModel model) { return info(model).hue; }

Vec4 convert(ColorModel from, ColorModel to, const Vec4& values) {
  if (from == to) return values;
  return info(to).from_rgb(info(from).to_rgb(values));
}

std::vector<double> convert(ColorModel from, ColorModel to, std::span<const double> values) {
  const int n_from = component_count(from), n_to = component_count(to);
  if (values.size() != size_t(n_from))
    throw InvalidInput(
        fmt::format("color model {} has {} components, got {}", model_name(from), n_from, values.size()));
  std::vector<double> out(static_cast<size_t>(n_to));
  convert_many(from, to, values, out);
  return out;
}

void convert_many(ColorModel from, ColorModel to, std::span<const double> in, std::span<double> out) {
  const size_t n_from = size_t(component_count(from)), n_to = size_t(component_count(to));
  const size_t count = in.size() / n_from;
  if (in.size() % n_from != 0 || out.size() != count * n_to)
    throw InvalidInput(fmt::format("convert_many: {} {} values and {} {} values are not the same number of colors",
                                   in.size(), model_name(from), out.size(), model_name(to)));
  // Each color on its own: chunks in parallel give the same values for any thread count. The table's conversions are
  // looked up once, not per color.
  const ModelInfo &source = info(from), &target = info(to);
  parallel_for(0, int64_t(count), 16384, [&](int64_t begin, int64_t end) {
    // The hue models from the hub two colors at a time (rows.hpp): the same values as one at a time.
    if (from == ColorModel::rgb && (to == ColorModel::hsv || to == ColorModel::hls)) {
      const auto first = size_t(begin) * 3, size = size_t(end - begin) * 3;
      (to == ColorModel::hsv ? detail::rgb_to_hsv_rows : detail::rgb_to_hls_rows)(in.subspan(first, size),
                                                                                  out.subspan(first, size));
      return;
    }
    for (auto i = size_t(begin); i < size_t(end); ++i) {
      Vec4 v(0.0);
      for (size_t c = 0; c < n_from; ++c) v[int(c)] = in[i * n_from + c];
      const Vec4 result = from == to                ? v
                          : from == ColorModel::rgb ? target.from_rgb(Vec3(v))  // the hub: one conversion
                          : to == ColorModel::rgb   ? Vec4(source.to_rgb(v), 0.0)
                                                    : target.from_rgb(source.to_rgb(v));
      for (size_t c = 0; c < n_to; ++c) out[i * n_to + c] = result[int(c)];
    }
  });
}

double full_turn(HueUnit unit) {
  switch (unit) {
    case HueUnit::degrees:
      return 360.0;
    case HueUnit::turns:
      return 1.0;
    case HueUnit::radians:
      return 2.0 * kPi;
  }
  throw InternalError("full_turn: unknown hue unit");
}

HueUnit parse_hue_unit(std::string_view name) {
  if (name == "degrees") return HueUnit::degrees;
  if (name == "turns") return HueUnit::turns;
  if (name == "radians") return HueUnit::radians;
  throw InvalidInput(fmt::format("unknown hue unit '{}' (expected degrees, turns or radians)", printable(name)));
}

}  // namespace tessera
