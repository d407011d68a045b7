#pragma once
// Image comparison metrics for tests: images are compared with a tolerance, never by eye alone.
//
// Every metric runs over all pixels and all channels (alpha included for RGBA) and throws InvalidInput when the two
// images differ in size.
#include "tessera/image/image.hpp"

namespace tessera {

/// Largest absolute difference over all pixels and channels (0 for two empty images).
double max_abs_difference(const ImageRGB& a, const ImageRGB& b);
double max_abs_difference(const ImageRGBA& a, const ImageRGBA& b);
double max_abs_difference(const ImageRGBA8& a, const ImageRGBA8& b);
double max_abs_difference(const DepthImage& a, const DepthImage& b);

/// Root mean square difference over all pixels and channels: sqrt(sum (a - b)^2 / (pixels * channels)).
double rmse(const ImageRGB& a, const ImageRGB& b);
double rmse(const ImageRGBA& a, const ImageRGBA& b);
double rmse(const ImageRGBA8& a, const ImageRGBA8& b);
double rmse(const DepthImage& a, const DepthImage& b);

/// Peak signal-to-noise ratio in dB, 20 log10(peak / rmse), for the given peak value (1 for float, 255 for 8-bit);
/// infinity if the images are equal.
double psnr(const ImageRGB& a, const ImageRGB& b, double peak = 1.0);
double psnr(const ImageRGBA& a, const ImageRGBA& b, double peak = 1.0);
double psnr(const ImageRGBA8& a, const ImageRGBA8& b, double peak = 255.0);
double psnr(const DepthImage& a, const DepthImage& b, double peak = 1.0);

/// Number of pixels where any channel differs by more than `tolerance` (a NaN in either image counts as different).
long long count_differing_pixels(const ImageRGB& a, const ImageRGB& b, double tolerance = 0.0);
long long count_differing_pixels(const ImageRGBA& a, const ImageRGBA& b, double tolerance = 0.0);
long long count_differing_pixels(const ImageRGBA8& a, const ImageRGBA8& b, int tolerance = 0);
long long count_differing_pixels(const DepthImage& a, const DepthImage& b, double tolerance = 0.0);

}  // namespace tessera
