#include "gallery.hpp"

#include <cstdlib>
#include <algorithm>
#include <sstream>

#include "tessera/core/atomic_file.hpp"
#include "tessera/core/error.hpp"
#include "tessera/image/image_io.hpp"

namespace tessera::examples {
namespace {
std::vector<Example>& registry() {
  static std::vector<Example> examples;
  return examples;
}

std::string html_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}
}  // namespace

Gallery::Gallery(std::filesystem::path dir) : dir_(std::move(dir)) {
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  if (ec) throw IoError(fmt::format("cannot create folder '{}': {}", dir_.string(), ec.message()));
}

void Gallery::add(const std::string& file, const ImageRGB& image, const std::string& caption) {
  write_image(dir_ / file, image);
  pictures_.push_back({file, caption});
}

void Gallery::add(const std::string& file, const ImageRGBA8& image, const std::string& caption) {
  write_image(dir_ / file, image);
  pictures_.push_back({file, caption});
}

void Gallery::add_file(const std::string& file, const std::string& caption) { pictures_.push_back({file, caption}); }

void Gallery::section(const std::string& title) { sections_.emplace_back(pictures_.size(), title); }

void Gallery::write_index(const std::string& title) const {
  std::ostringstream html;
  html << "<!doctype html>\n<html><head><meta charset=\"utf-8\"><title>" << html_escape(title) << "</title>\n"
       << "<style>body{font-family:sans-serif;max-width:1200px;margin:auto;background:#fafafa}"
          "figure{display:inline-block;margin:8px;vertical-align:top;max-width:360px}"
          "img{max-width:360px;border:1px solid #ccc;image-rendering:pixelated}"
          "figcaption{font-size:13px}</style></head><body>\n<h1>"
       << html_escape(title) << "</h1>\n";
  size_t next_section = 0;
  for (size_t i = 0; i < pictures_.size(); ++i) {
    while (next_section < sections_.size() && sections_[next_section].first == i)
      html << "<h2>" << html_escape(sections_[next_section++].second) << "</h2>\n";
    html << "<figure><a href=\"" << html_escape(pictures_[i].file) << "\"><img src=\"" << html_escape(pictures_[i].file)
         << "\" alt=\"" << html_escape(pictures_[i].caption) << "\"></a><figcaption>" << html_escape(pictures_[i].caption)
         << "</figcaption></figure>\n";
  }
  html << "</body></html>\n";
  write_file_atomic(dir_ / "index.html", html.str());
}

void paste(ImageRGB& sheet, const ImageRGB& tile, int x0, int y0) {
  for (int y = 0; y < tile.height(); ++y)
    for (int x = 0; x < tile.width(); ++x)
      if (sheet.contains(x0 + x, y0 + y)) sheet(x0 + x, y0 + y) = tile(x, y);
}

std::filesystem::path shared_data() {
  const char* env = std::getenv("TESSERA_SHARED_DATA");
  return env ? env : "../shared/data";
}

ImageRGB side_by_side(const std::vector<ImageRGB>& panels) {
  int width = 0, height = 0;
  for (const ImageRGB& p : panels) width += p.width(), height = std::max(height, p.height());
  ImageRGB sheet(width, height, glm::vec3(1.0f));
  int x0 = 0;
  for (const ImageRGB& p : panels) {
    paste(sheet, p, x0);
    x0 += p.width();
  }
  return sheet;
}

int register_example(const Example& example) {
  registry().push_back(example);
  return 0;
}

std::vector<Example> all_examples() {
  auto examples = registry();
  std::sort(examples.begin(), examples.end(),
            [](const Example& a, const Example& b) { return std::string(a.name) < std::string(b.name); });
  return examples;
}

size_t run_examples(const std::filesystem::path& dir, const std::vector<std::string>& prefixes) {
  Gallery gallery(dir);
  for (const Example& e : all_examples()) {
    const std::string name = e.name;
    const bool selected = prefixes.empty() || std::any_of(prefixes.begin(), prefixes.end(), [&](const std::string& p) {
                            return name.rfind(p, 0) == 0;
                          });
    if (!selected) continue;
    gallery.section(fmt::format("{}: {}", e.name, e.title));
    e.run(gallery);
  }
  gallery.write_index("Tessera gallery");
  return gallery.pictures().size();
}

}  // namespace tessera::examples
