#include "tessera/raster3d/framebuffer.hpp"

#include <fmt/format.h>

#include "tessera/raster3d/pipeline.hpp"

namespace tessera::raster3d {

Framebuffer::Framebuffer(int width, int height) : scratch_(std::make_unique<detail::RasterScratch>()) {
  if (width < 1 || height < 1) throw InvalidInput(fmt::format("framebuffer size {}x{} is invalid", width, height));
  color_ = ImageRGBA8(width, height, glm::u8vec4(0, 0, 0, 255));
  front_ = color_;
  depth_ = Image<uint32_t>(width, height, kDepthMax);
}

Framebuffer::~Framebuffer() = default;
Framebuffer::Framebuffer(Framebuffer&&) noexcept = default;
Framebuffer& Framebuffer::operator=(Framebuffer&&) noexcept = default;

void Framebuffer::clear_color(const Vec3f& color) { color_.fill(to_color8(color)); }

void Framebuffer::clear_depth(double depth) { depth_.fill(depth_to_unorm24(depth)); }

void Framebuffer::swap() { std::swap(color_, front_); }

ImageRGB Framebuffer::color_rgb() const {
  ImageRGB out(width(), height());
  for (int y = 0; y < height(); ++y)
    for (int x = 0; x < width(); ++x) out(x, y) = Vec3f(color_(x, y)) / 255.0f;
  return out;
}

DepthImage Framebuffer::depth_image() const {
  DepthImage out(width(), height());
  for (int y = 0; y < height(); ++y)
    for (int x = 0; x < width(); ++x) out(x, y) = float(double(depth_(x, y)) / kDepthMax);
  return out;
}

}  // namespace tessera::raster3d
