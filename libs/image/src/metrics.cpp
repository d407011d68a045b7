#include "tessera/image/metrics.hpp"

#include <cmath>
#include <limits>
#include <type_traits>

#include "tessera/core/error.hpp"

namespace tessera {
namespace {

// Channels of a pixel type: glm vectors have length(), scalars one channel.
template <class T>
constexpr int channel_count() {
  if constexpr (std::is_arithmetic_v<T>)
    return 1;
  else
    return T::length();
}

template <class T>
double channel(const T& pixel, int c) {
  if constexpr (std::is_arithmetic_v<T>)
    return double(pixel);
  else
    return double(pixel[c]);
}

template <class T>
void check_same_size(const Image<T>& a, const Image<T>& b) {
  if (a.width() != b.width() || a.height() != b.height())
    throw InvalidInput(
        fmt::format("cannot compare a {}x{} image with a {}x{} image", a.width(), a.height(), b.width(), b.height()));
}

// Calls visit(pixel index, channel difference a - b) for every channel of every pixel.
template <class T, class Visit>
void for_each_difference(const Image<T>& a, const Image<T>& b, Visit&& visit) {
  check_same_size(a, b);
  const auto pa = a.pixels(), pb = b.pixels();
  for (size_t i = 0; i < pa.size(); ++i)
    for (int c = 0; c < channel_count<T>(); ++c) visit(i, channel(pa[i], c) - channel(pb[i], c));
}

template <class T>
double max_abs_impl(const Image<T>& a, const Image<T>& b) {
  double worst = 0.0;
  for_each_difference(a, b, [&](size_t, double d) {
    if (!(std::abs(d) <= worst)) worst = std::abs(d);  // keeps a NaN difference
  });
  return worst;
}

template <class T>
double rmse_impl(const Image<T>& a, const Image<T>& b) {
  double sum = 0.0;
  for_each_difference(a, b, [&](size_t, double d) { sum += d * d; });
  const double count = double(a.pixels().size()) * channel_count<T>();
  return count > 0 ? std::sqrt(sum / count) : 0.0;
}

template <class T>
double psnr_impl(const Image<T>& a, const Image<T>& b, double peak) {
  const double error = rmse_impl(a, b);
  return error == 0.0 ? std::numeric_limits<double>::infinity() : 20.0 * std::log10(peak / error);
}

template <class T>
long long count_impl(const Image<T>& a, const Image<T>& b, double tolerance) {
  long long count = 0;
  size_t last = std::numeric_limits<size_t>::max();
  for_each_difference(a, b, [&](size_t i, double d) {
    if (!(std::abs(d) <= tolerance) && i != last) {
      ++count;
      last = i;
    }
  });
  return count;
}

}  // namespace

double max_abs_difference(const ImageRGB& a, const ImageRGB& b) { return max_abs_impl(a, b); }
double max_abs_difference(const ImageRGBA& a, const ImageRGBA& b) { return max_abs_impl(a, b); }
double max_abs_difference(const ImageRGBA8& a, const ImageRGBA8& b) { return max_abs_impl(a, b); }
double max_abs_difference(const DepthImage& a, const DepthImage& b) { return max_abs_impl(a, b); }

double rmse(const ImageRGB& a, const ImageRGB& b) { return rmse_impl(a, b); }
double rmse(const ImageRGBA& a, const ImageRGBA& b) { return rmse_impl(a, b); }
double rmse(const ImageRGBA8& a, const ImageRGBA8& b) { return rmse_impl(a, b); }
double rmse(const DepthImage& a, const DepthImage& b) { return rmse_impl(a, b); }

double psnr(const ImageRGB& a, const ImageRGB& b, double peak) { return psnr_impl(a, b, peak); }
double psnr(const ImageRGBA& a, const ImageRGBA& b, double peak) { return psnr_impl(a, b, peak); }
double psnr(const ImageRGBA8& a, const ImageRGBA8& b, double peak) { return psnr_impl(a, b, peak); }
double psnr(const DepthImage& a, const DepthImage& b, double peak) { return psnr_impl(a, b, peak); }

long long count_differing_pixels(const ImageRGB& a, const ImageRGB& b, double tolerance) {
  return count_impl(a, b, tolerance);
}
long long count_differing_pixels(const ImageRGBA& a, const ImageRGBA& b, double tolerance) {
  return count_impl(a, b, tolerance);
}
long long count_differing_pixels(const ImageRGBA8& a, const ImageRGBA8& b, int tolerance) {
  return count_impl(a, b, double(tolerance));
}
long long count_differing_pixels(const DepthImage& a, const DepthImage& b, double tolerance) {
  return count_impl(a, b, tolerance);
}

}  // namespace tessera
