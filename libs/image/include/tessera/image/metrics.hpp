#pragma once
// Image comparison metrics for tests: images are compared with a tolerance, never by eye alone.
#include "tessera/image/image.hpp"

namespace tessera {

/// Largest absolute difference over all pixels and channels. Throws InvalidInput if the sizes differ.
double max_abs_difference(const ImageRGB& a, const ImageRGB& b);
double max_abs_difference(const ImageRGBA8& a, const ImageRGBA8& b);
/// Root mean square difference over all pixels and channels.
double rmse(const ImageRGB& a, const ImageRGB& b);
double rmse(const ImageRGBA8& a, const ImageRGBA8& b);
/// Peak signal-to-noise ratio in dB for the given peak value (1 for float, 255 for 8-bit); infinity if equal.
double psnr(const ImageRGB& a, const ImageRGB& b, double peak = 1.0);
double psnr(const ImageRGBA8& a, const ImageRGBA8& b, double peak = 255.0);
/// Number of pixels where any channel differs by more than `tolerance`.
long long count_differing_pixels(const ImageRGB& a, const ImageRGB& b, double tolerance = 0.0);
long long count_differing_pixels(const ImageRGBA8& a, const ImageRGBA8& b, int tolerance = 0);

}  // namespace tessera
