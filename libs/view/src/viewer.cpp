#include "tessera/view/viewer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>

#include "tessera/core/error.hpp"
#include "tessera/core/parallel.hpp"
#include "tessera/image/animation.hpp"
#include "tessera/raster2d/font.hpp"
#include "tessera/raster3d/framebuffer.hpp"
#include "view_mode.hpp"

namespace tessera {
namespace detail {

std::unique_ptr<ViewMode> make_view_mode(const Viewable& v, ViewerOptions o) {
  if (o.up_axis < 0) o.up_axis = v.kind == ViewableKind::patches ? 2 : 1;
  switch (v.kind) {
    case ViewableKind::mesh:
      return make_mesh_mode(v, o);
    case ViewableKind::scene:
      // A scene's materials name their own programs (docs/scene-format.md).
      if (!o.vertex_shader.empty() || !o.fragment_shader.empty())
        throw InvalidInput(v.name + ": a scene's shaders are its materials' (\"shader\"), not the viewer's");
      return make_scene_mode(v, o);
    case ViewableKind::volume:
      return make_volume_mode(v, o);
    case ViewableKind::patches:
      return make_patch_mode(v, o);
  }
  throw InternalError("make_view_mode: unknown kind");
}

void to_frame(const ImageRGB& picture, ImageRGBA8& out, float divisor) {
  parallel_for(0, picture.height(), 16, [&picture, &out, divisor](int64_t y0, int64_t y1) {
    const auto width = size_t(picture.width());  // a local: byte stores cannot alias it
    for (int y = int(y0); y < int(y1); ++y) {
      const auto* in = reinterpret_cast<const float*>(picture.row(y));
      auto* o = reinterpret_cast<uint8_t*>(out.row(y));
      for (size_t x = 0; x < width; ++x) {
        o[4 * x] = raster3d::to_unorm8(in[3 * x] / divisor);
        o[4 * x + 1] = raster3d::to_unorm8(in[3 * x + 1] / divisor);
        o[4 * x + 2] = raster3d::to_unorm8(in[3 * x + 2] / divisor);
        o[4 * x + 3] = 255;
      }
    }
  });
}

}  // namespace detail

namespace {

/// Stamps `lines` of the built-in font (font.hpp) at `scale` device pixels per font unit, the first baseline at
/// (x, y), in `color`, over a darkened box with a margin of 2 units (clipped to the picture).
void draw_text_box(ImageRGBA8& image, const std::vector<std::string>& lines, int x, int y, int scale,
                   glm::u8vec4 color) {
  std::string text;
  int columns = 0;
  for (const std::string& line : lines) {
    text += (text.empty() ? "" : "\n") + line;
    columns = std::max(columns, font::text_width(line));
  }
  const int margin = 2 * scale;
  const int x0 = std::max(0, x - margin), x1 = std::min(image.width(), x + columns * scale + margin);
  const int y0 = std::max(0, y - font::kAscent * scale - margin);
  const int y1 =
      std::min(image.height(), y + (font::kDescent + font::kLineHeight * (int(lines.size()) - 1)) * scale + margin);
  for (int py = y0; py < y1; ++py)
    for (int px = x0; px < x1; ++px) {
      glm::u8vec4& p = image(px, py);
      p = glm::u8vec4(p.x * 3 / 10, p.y * 3 / 10, p.z * 3 / 10, 255);
    }
  for (const font::TextRun& run : font::text_runs(text))
    for (int dy = 0; dy < scale; ++dy) {
      const int py = y + run.y * scale + dy;
      if (py < 0 || py >= image.height()) continue;
      for (int px = std::max(0, x + run.x0 * scale); px < std::min(image.width(), x + run.x1 * scale); ++px)
        image(px, py) = color;
    }
}

/// The font's scale for a picture: one device pixel a font unit up to 360 rows, then one more per 360.
int text_scale(int height) { return std::max(1, height / 360); }

/// `text` cut to `columns` characters, with an ellipsis when cut.
std::string fit(const std::string& text, int columns) {
  if (int(text.size()) <= columns) return text;
  return columns > 3 ? text.substr(0, size_t(columns - 3)) + "..." : text.substr(0, size_t(std::max(columns, 0)));
}

}  // namespace

std::string_view shading_name(ViewShading shading) {
  switch (shading) {
    case ViewShading::unlit:
      return "unlit";
    case ViewShading::flat:
      return "flat";
    case ViewShading::gouraud:
      return "gouraud";
    case ViewShading::phong:
      return "phong";
    case ViewShading::wireframe:
      return "wireframe";
    case ViewShading::normals:
      return "normals";
  }
  return "?";
}

std::vector<std::string> Viewer::help_lines() {
  return {"left drag: orbit (arcball)     right/middle drag: pan     wheel: zoom",
          "1-6: unlit flat gouraud phong wireframe normals     w: edges",
          "+ -: subdivision level (patches: tessellation)     d: shadows     t: texture",
          "Tab: rasterizer / ray tracer (scenes), iso-surface / volume rendering (volumes)",
          "up down: iso value or window level     left right: window width",
          "s: screenshot     r: reset view     h: this help     Escape: quit"};
}

Viewer::Viewer(Viewable viewable, ViewerOptions options)
    : viewable_(std::move(viewable)), options_(std::move(options)) {
  if (options_.width < 1 || options_.height < 1)
    throw InvalidInput(fmt::format("viewer size {}x{}: expected at least 1x1", options_.width, options_.height));
  if (options_.trace_samples < 1)
    throw InvalidInput(fmt::format("trace samples {}: expected at least 1", options_.trace_samples));
  if (options_.up_axis != -1 && options_.up_axis != 1 && options_.up_axis != 2)
    throw InvalidInput(fmt::format("up axis {}: expected 1 (y) or 2 (z)", options_.up_axis));
  if (options_.orbit_frames < 0)
    throw InvalidInput(fmt::format("orbit frames {}: expected 0 (no turntable) or more", options_.orbit_frames));
}

Viewer::~Viewer() = default;

void Viewer::setup() {
  size(options_.width, options_.height, Renderer::p3d);
  mode_ = detail::make_view_mode(viewable_, options_);
  control_ = mode_->home(double(width) / height);
}

Camera Viewer::current_camera() const {
  OrbitControl c = control_;
  if (options_.orbit_frames > 0) {
    const double turn = 2 * kPi * double(frame_count - 1) / options_.orbit_frames;
    c.set_orientation(c.turn_about_up(turn) * c.orientation());
  }
  return c.camera(double(width) / height);
}

void Viewer::draw() {
  const auto start = std::chrono::steady_clock::now();
  ImageRGBA8& frame = context().framebuffer().color();
  if (mode_->poll()) moved_ = true;
  mode_->render(current_camera(), moved_ || options_.orbit_frames > 0, frame);
  moved_ = false;
  last_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ++stats_.renders;
  stats_.render_seconds += last_seconds_;
  stats_.triangles = mode_->triangles();
  if (!screenshot_.empty()) {  // the picture alone, before the text
    save_frame(screenshot_);
    note_ = fmt::format("saved {}", numbered_frame_path(screenshot_, frame_count).string());
    screenshot_.clear();
  }
  status_ = mode_->describe();
  if (!note_.empty()) status_ += fmt::format(" [{}]", note_);
  note_.clear();
  const int scale = text_scale(height);
  if (options_.status_line) {
    std::string line = status_;
    if (options_.frame_time) line += fmt::format("  {:.1f} ms", 1000 * last_seconds_);
    const int columns = (width - 8 * scale) / (font::kAdvance * scale);
    draw_text_box(frame, {fit(line, columns)}, 4 * scale, height - (font::kDescent + 3) * scale, scale,
                  glm::u8vec4(235, 235, 235, 255));
  }
  if (help_)
    draw_text_box(frame, help_lines(), 6 * scale, (font::kAscent + 6) * scale, scale, glm::u8vec4(255, 230, 150, 255));
  // Idle pictures are not drawn again until something changes (events call redraw()); watched shader files are
  // looked at every frame.
  if (options_.orbit_frames > 0 || mode_->refining() || options_.watch_shaders)
    loop();
  else
    no_loop();
}

void Viewer::mouse_pressed() {
  if (mouse_button == MouseButton::left)
    control_.begin_rotate(mouse_x, mouse_y, width, height);
  else
    control_.begin_pan(mouse_x, mouse_y);
}

void Viewer::mouse_dragged() {
  if (mouse_button == MouseButton::left)
    control_.rotate_to(mouse_x, mouse_y, width, height);
  else
    control_.pan_to(mouse_x, mouse_y, height);
  changed();
}

void Viewer::mouse_wheel(double delta) {
  control_.zoom(delta);
  changed();
}

void Viewer::key_pressed() {
  if (key == 's') {
    screenshot_ = options_.screenshot;
    redraw();
  } else if (key == 'r') {
    control_.reset();
    changed();
  } else if (key == 'h') {
    help_ = !help_;
    redraw();
  } else if (mode_->key(key, key_code)) {
    changed();
  }
}

}  // namespace tessera
