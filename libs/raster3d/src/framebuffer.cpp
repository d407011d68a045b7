#include "tessera/raster3d/framebuffer.hpp"

#include <fmt/format.h>

#include "tessera/core/parallel.hpp"
#include "tessera/raster3d/pipeline.hpp"

namespace tessera::raster3d {

Framebuffer::Framebuffer(int width, int height) : Framebuffer(width, height, true) {}

Framebuffer Framebuffer::depth_only(int width, int height) { return Framebuffer(width, height, false); }

Framebuffer::Framebuffer(int width, int height, bool color) : scratch_(std::make_unique<detail::RasterScratch>()) {
  if (width < 1 || height < 1) throw InvalidInput(fmt::format("framebuffer size {}x{} is invalid", width, height));
  depth_ = Image<uint32_t>(width, height, kDepthMax);
  if (!color) return;
  color_ = ImageRGBA8(width, height, glm::u8vec4(0, 0, 0, 255));
  front_ = color_;
  stencil_ = Image<uint8_t>(width, height, 0);
}

// A raster job in flight writes the buffers through this object: everything that moves, frees or writes them from
// the caller's side waits for it first.
void Framebuffer::wait_for_raster() noexcept {
  if (scratch_) detail::wait_raster(*scratch_);
}

Framebuffer::~Framebuffer() { wait_for_raster(); }

Framebuffer::Framebuffer(Framebuffer&& other) noexcept { *this = std::move(other); }

Framebuffer& Framebuffer::operator=(Framebuffer&& other) noexcept {
  wait_for_raster();
  other.wait_for_raster();
  color_ = std::move(other.color_);
  front_ = std::move(other.front_);
  depth_ = std::move(other.depth_);
  stencil_ = std::move(other.stencil_);
  scratch_ = std::move(other.scratch_);
  return *this;
}

void Framebuffer::clear_color(const Vec3f& color, float alpha) {
  wait_for_raster();
  color_.fill(to_color8(Vec4f(color, alpha)));
}

void Framebuffer::clear_depth(double depth) {
  wait_for_raster();
  depth_.fill(depth_to_unorm24(depth));
}

void Framebuffer::clear_stencil(uint8_t value) {
  wait_for_raster();
  stencil_.fill(value);
}

void Framebuffer::swap() {
  wait_for_raster();
  std::swap(color_, front_);
}

ImageRGB Framebuffer::color_rgb() const {
  // Rows in parallel: every rendered picture goes through here (the viewer's frame time).
  ImageRGB out(color_.width(), color_.height());
  parallel_for(0, out.height(), 16, [&](int64_t y0, int64_t y1) {
    for (int y = int(y0); y < int(y1); ++y)
      for (int x = 0; x < out.width(); ++x) out(x, y) = Vec3f(color_(x, y)) / 255.0f;
  });
  return out;
}

DepthImage Framebuffer::depth_image() const {
  DepthImage out(width(), height());
  for (int y = 0; y < height(); ++y)
    for (int x = 0; x < width(); ++x) out(x, y) = float(double(depth_(x, y)) / kDepthMax);
  return out;
}

}  // namespace tessera::raster3d
