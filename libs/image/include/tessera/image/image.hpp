#pragma once
// Image<T>: a width x height grid of pixels, row 0 at the top, rows contiguous; and ImageView<T>, a window into one.
//
// Pixel (x, y) covers [x, x+1) x [y, y+1) and its center is (x + 0.5, y + 0.5) (DESIGN.md section 3).
#include <fmt/format.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <type_traits>
#include <vector>

#include "tessera/core/error.hpp"

namespace tessera {

/// A non-owning window of an image: width x height pixels, `stride` pixels from one row to the next.
template <class T>
class ImageView {
 public:
  /// A view of `width` x `height` pixels starting at `data`; rows are `stride` pixels apart (stride >= width).
  ImageView(T* data, int width, int height, ptrdiff_t stride)
      : data_(data), width_(width), height_(height), stride_(stride) {}
  /// A read-only view of a writable one.
  template <class U>
  requires std::is_same_v<T, const U> ImageView(
      const ImageView<U>& other)  // NOLINT(google-explicit-constructor): mirrors T* -> const T*
      : data_(other.row(0)), width_(other.width()), height_(other.height()), stride_(other.stride()) {}

  /// Size in pixels.
  int width() const { return width_; }
  int height() const { return height_; }
  /// Pixels from one row to the next.
  ptrdiff_t stride() const { return stride_; }
  /// Pixel (x, y); no bounds check (use contains()).
  T& operator()(int x, int y) const { return data_[y * stride_ + x]; }
  /// The first pixel of row y.
  T* row(int y) const { return data_ + y * stride_; }
  /// True when (x, y) is inside.
  bool contains(int x, int y) const { return x >= 0 && y >= 0 && x < width_ && y < height_; }
  /// Sets every pixel to v.
  void fill(const T& v) const {
    for (int y = 0; y < height_; ++y)
      for (int x = 0; x < width_; ++x) (*this)(x, y) = v;
  }
  /// The sub-window [x, x+w) x [y, y+h), clipped to this view.
  ImageView sub(int x, int y, int w, int h) const {
    const int x0 = std::max(0, x), y0 = std::max(0, y);
    const int x1 = std::min(width_, x + w), y1 = std::min(height_, y + h);
    return ImageView(data_ + y0 * stride_ + x0, std::max(0, x1 - x0), std::max(0, y1 - y0), stride_);
  }

 private:
  T* data_;
  int width_, height_;
  ptrdiff_t stride_;
};

/// An owning image of pixels T (float RGB, float RGBA, 8-bit RGBA, float depth: see the aliases below).
template <class T>
class Image {
 public:
  using Pixel = T;

  /// An empty 0 x 0 image.
  Image() = default;
  /// A width x height image filled with `value`. Throws InvalidInput for negative or absurd sizes.
  Image(int width, int height, const T& value = T{}) : width_(width), height_(height) {
    if (width < 0 || height < 0 || (width > 0 && height > (int64_t(1) << 31) / width))
      throw InvalidInput(fmt::format("image size {}x{} is invalid", width, height));
    pixels_.assign(size_t(width) * size_t(height), value);
  }

  /// Size in pixels.
  int width() const { return width_; }
  int height() const { return height_; }
  /// True for a 0 x 0 (or 0 x n) image.
  bool empty() const { return pixels_.empty(); }
  /// Pixel (x, y); no bounds check (use contains()).
  T& operator()(int x, int y) { return pixels_[size_t(y) * size_t(width_) + size_t(x)]; }
  const T& operator()(int x, int y) const { return pixels_[size_t(y) * size_t(width_) + size_t(x)]; }
  /// Bounds-checked pixel access; throws InvalidInput outside.
  T& at(int x, int y) {
    if (!contains(x, y)) throw InvalidInput(fmt::format("pixel ({}, {}) is outside {}x{}", x, y, width_, height_));
    return (*this)(x, y);
  }
  const T& at(int x, int y) const { return const_cast<Image&>(*this).at(x, y); }
  /// True when (x, y) is inside.
  bool contains(int x, int y) const { return x >= 0 && y >= 0 && x < width_ && y < height_; }
  /// The first pixel of row y.
  T* row(int y) { return pixels_.data() + size_t(y) * size_t(width_); }
  const T* row(int y) const { return pixels_.data() + size_t(y) * size_t(width_); }
  /// All pixels, row-major from the top row.
  std::span<T> pixels() { return pixels_; }
  std::span<const T> pixels() const { return pixels_; }
  /// Sets every pixel to v.
  void fill(const T& v) { std::fill(pixels_.begin(), pixels_.end(), v); }
  /// A view of the whole image or of a sub-rectangle.
  ImageView<T> view() { return ImageView<T>(pixels_.data(), width_, height_, width_); }
  ImageView<const T> view() const { return ImageView<const T>(pixels_.data(), width_, height_, width_); }
  ImageView<T> view(int x, int y, int w, int h) { return view().sub(x, y, w, h); }
  ImageView<const T> view(int x, int y, int w, int h) const { return view().sub(x, y, w, h); }

 private:
  int width_ = 0, height_ = 0;
  std::vector<T> pixels_;
};

using ImageRGB = Image<glm::vec3>;      ///< linear float RGB, the renderers' output
using ImageRGBA = Image<glm::vec4>;     ///< linear float RGBA
using ImageRGBA8 = Image<glm::u8vec4>;  ///< 8-bit RGBA, what 8-bit files hold
using DepthImage = Image<float>;        ///< one float per pixel (depth buffers, scalar fields)

}  // namespace tessera
