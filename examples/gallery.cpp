#include "gallery.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string_view>

#include "tessera/core/atomic_file.hpp"
#include "tessera/core/error.hpp"
#include "tessera/core/progress.hpp"
#include "tessera/image/image_io.hpp"
#include "tessera/image/metrics.hpp"

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
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}
}  // namespace

Gallery::Gallery(std::filesystem::path dir, DataFolder data, WriteOptions write)
    : dir_(std::move(dir)), data_(std::move(data)), write_(write) {
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  if (ec) throw IoError(fmt::format("cannot create folder '{}': {}", dir_.string(), ec.message()));
}

void Gallery::add(const std::string& file, const ImageRGB& image, const std::string& caption) {
  write_image(dir_ / file, image, write_);
  pictures_.push_back({file, caption});
}

void Gallery::add(const std::string& file, const ImageRGBA8& image, const std::string& caption) {
  write_image(dir_ / file, image, write_);
  pictures_.push_back({file, caption});
}

std::optional<std::filesystem::path> Gallery::data_file(const std::string& relative, const std::string& stand_in) {
  if (!data_.dir.empty()) {
    std::filesystem::path path = data_.dir / relative;
    if (std::filesystem::exists(path)) return path;
  }
  ++stand_ins_;
  const std::string where = data_.dir.empty() ? "no shared data folder found (give one with --data DIR or TESSERA_DATA)"
                                              : fmt::format("not in {} (from {})", data_.dir.string(), data_.source);
  std::fprintf(stderr, "tessera: warning: shared data file %s: %s; drawing a stand-in: %s\n", relative.c_str(),
               where.c_str(), stand_in.c_str());
  return std::nullopt;
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
         << "\" alt=\"" << html_escape(pictures_[i].caption) << "\"></a><figcaption>"
         << html_escape(pictures_[i].caption) << "</figcaption></figure>\n";
  }
  html << "</body></html>\n";
  write_file_atomic(dir_ / "index.html", html.str());
}

void paste(ImageRGB& sheet, const ImageRGB& tile, int x0, int y0) {
  for (int y = 0; y < tile.height(); ++y)
    for (int x = 0; x < tile.width(); ++x)
      if (sheet.contains(x0 + x, y0 + y)) sheet(x0 + x, y0 + y) = tile(x, y);
}

std::vector<DataFolder> default_data_folders() {
  std::vector<DataFolder> folders = {{"shared/data", "./shared/data"}, {"../shared/data", "../shared/data"}};
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec)
    for (std::filesystem::path dir = exe.parent_path(); !dir.empty(); dir = dir.parent_path()) {
      folders.push_back({dir / "shared/data", "shared/data above the executable"});
      if (dir == dir.root_path()) break;
    }
#ifdef TESSERA_CONFIGURED_DATA
  folders.push_back({TESSERA_CONFIGURED_DATA, "the build's TESSERA_SHARED_DATA"});
#endif
  return folders;
}

DataFolder locate_shared_data(const std::filesystem::path& option) {
  if (!option.empty()) return {option, "--data"};
  for (const char* name : {"TESSERA_DATA", "TESSERA_SHARED_DATA"})
    if (const char* env = std::getenv(name); env && *env) return {env, name};
  for (DataFolder& folder : default_data_folders())
    if (std::filesystem::is_directory(folder.dir)) return folder;
  return {};
}

namespace {
constexpr std::string_view kStandInPrefix = "STAND-IN (";
}  // namespace

std::string stand_in_caption(const std::string& what, const std::string& real, const std::string& caption) {
  return fmt::format("{}shared data not found; drawn instead of {}: {}): {}", kStandInPrefix, real, what, caption);
}

bool is_stand_in(const Picture& picture) { return picture.caption.starts_with(kStandInPrefix); }

Comparison compare_picture(const ImageRGBA8& picture, const ImageRGBA8& reference, const Tolerance& tolerance) {
  if (picture.width() != reference.width() || picture.height() != reference.height())
    return {false, fmt::format("size {}x{}, the reference is {}x{}", picture.width(), picture.height(),
                               reference.width(), reference.height())};
  const long long total = (long long)picture.width() * picture.height();
  const long long differing = count_differing_pixels(picture, reference, tolerance.levels);
  const auto allowed = (long long)std::floor(tolerance.pixels * double(total));
  const double db = psnr(picture, reference);
  const bool passed = differing <= allowed && db >= tolerance.min_psnr;
  return {passed, fmt::format("{} of {} pixels differ by more than {} levels (at most {} may), max difference {} "
                              "levels, PSNR {:.1f} dB (at least {:.1f})",
                              differing, total, tolerance.levels, allowed, max_abs_difference(picture, reference), db,
                              tolerance.min_psnr)};
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

RunSummary run_examples(const std::filesystem::path& dir, const RunOptions& options) {
  const std::vector<std::string>& prefixes = options.prefixes;
  std::vector<Example> selected;
  for (const Example& e : all_examples()) {
    const std::string name = e.name;
    if (prefixes.empty() ||
        std::any_of(prefixes.begin(), prefixes.end(), [&](const std::string& p) { return name.rfind(p, 0) == 0; }))
      selected.push_back(e);
  }
  Gallery gallery(dir, options.data, options.write);
  Progress progress("gallery", int64_t(selected.size()));
  for (const Example& e : selected) {
    gallery.section(fmt::format("{}: {}", e.name, e.title));
    e.run(gallery);
    progress.advance();
  }
  progress.done();
  gallery.write_index("Tessera gallery");
  return {gallery.pictures().size(), gallery.stand_ins(), gallery.pictures()};
}

}  // namespace tessera::examples
