#pragma once
// Color models by name and a generic conversion between any two of them (what `tessera color convert` uses).
//
// The models are those of color.hpp: rgb cmy cmyk hsv hls yiq xyz xyy srgb. CMYK has 4 components, the others 3.
// Conversions go through linear RGB: convert(from, to, v) = from_rgb_to(to_rgb_from(v)).
#include <array>
#include <span>
#include <string_view>
#include <vector>

#include "tessera/math/types.hpp"

namespace tessera {

/// A color model, in the order of the command line's list.
enum class ColorModel { rgb, cmy, cmyk, hsv, hls, yiq, xyz, xyy, srgb };

/// Every model, in enum order.
inline constexpr std::array<ColorModel, 9> kColorModels = {ColorModel::rgb, ColorModel::cmy, ColorModel::cmyk,
                                                           ColorModel::hsv, ColorModel::hls, ColorModel::yiq,
                                                           ColorModel::xyz, ColorModel::xyy, ColorModel::srgb};

/// The model's lower-case name: "rgb", "cmy", "cmyk", "hsv", "hls", "yiq", "xyz", "xyy", "srgb".
std::string_view model_name(ColorModel model);

/// The model named `name` (lower case, as model_name). Throws InvalidInput "unknown color model '...' (expected one
/// of rgb, cmy, ...)".
ColorModel parse_color_model(std::string_view name);

/// Number of components: 4 for CMYK, 3 for every other model.
int component_count(ColorModel model);

/// Index of the hue component (0 for HSV and HLS), or -1 for models without a hue.
int hue_index(ColorModel model);

/// Converts one color between models. `values` holds component_count(from) components (the rest are ignored); the
/// result holds component_count(to) components and zeros after them. Hue in turns (color.hpp). from == to returns
/// `values` unchanged. Throws InvalidInput only for xyY with y <= 0 and Y != 0.
Vec4 convert(ColorModel from, ColorModel to, const Vec4& values);

/// Converts one color given as exactly component_count(from) numbers; returns component_count(to) numbers.
/// Throws InvalidInput when the count is wrong, or as the Vec4 version.
std::vector<double> convert(ColorModel from, ColorModel to, std::span<const double> values);

/// Converts many colors stored contiguously (component_count(from) numbers each in `in`, component_count(to) each
/// in `out`), with no allocation per color, in parallel (the same values for any thread count): the path for arrays.
/// Throws InvalidInput when the sizes do not hold the same whole number of colors, or as the Vec4 version.
void convert_many(ColorModel from, ColorModel to, std::span<const double> in, std::span<double> out);

/// Units for hue on the command line (the library uses turns).
enum class HueUnit { degrees, turns, radians };

/// The number of `unit`s in one full turn: 360, 1 or 2 pi.
double full_turn(HueUnit unit);

/// The unit named "degrees", "turns" or "radians". Throws InvalidInput for anything else.
HueUnit parse_hue_unit(std::string_view name);

}  // namespace tessera
