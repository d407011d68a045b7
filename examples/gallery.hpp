#pragma once
// The examples' registry and the gallery they feed.
//
// Each numbered example (examples/NN_name.cpp) is a function that draws one or more pictures and hands them to a
// Gallery. The same function runs as its own program (a test) and inside `tessera gallery` / `tessera demo`.
#include <filesystem>
#include <string>
#include <vector>

#include "tessera/image/image.hpp"

namespace tessera::examples {

/// One picture of the gallery.
struct Picture {
  std::string file;     ///< file name inside the gallery folder, e.g. "01_pink_pixel.png"
  std::string caption;  ///< one sentence for index.html
};

/// Collects pictures into a folder; write_index() makes index.html with a caption per picture.
class Gallery {
 public:
  /// Creates the folder if needed. Throws IoError when it cannot.
  explicit Gallery(std::filesystem::path dir);
  /// Writes an image (PNG, atomically) under `file` and records its caption.
  void add(const std::string& file, const ImageRGB& image, const std::string& caption);
  void add(const std::string& file, const ImageRGBA8& image, const std::string& caption);
  /// Records a file the example wrote itself (e.g. an SVG) under `file` in dir().
  void add_file(const std::string& file, const std::string& caption);
  /// The folder pictures go to.
  const std::filesystem::path& dir() const { return dir_; }
  /// Everything added so far, in order.
  const std::vector<Picture>& pictures() const { return pictures_; }
  /// Writes dir()/index.html listing every picture with its caption, grouped by example title.
  void write_index(const std::string& title) const;
  /// Starts a new section (an example's title) for the pictures that follow.
  void section(const std::string& title);

 private:
  std::filesystem::path dir_;
  std::vector<Picture> pictures_;
  std::vector<std::pair<size_t, std::string>> sections_;  // (first picture index, title)
};

/// Copies `tile` into `sheet` with its top-left corner at (x0, y0), clipped to the sheet (contact sheets of panels).
void paste(ImageRGB& sheet, const ImageRGB& tile, int x0, int y0 = 0);
/// Panels placed left to right, top-aligned, on a white sheet as tall as the tallest. Precondition: not empty.
ImageRGB side_by_side(const std::vector<ImageRGB>& panels);

/// The shared data folder: $TESSERA_SHARED_DATA, else ../shared/data. Examples that read from it draw generated
/// stand-ins when a file is missing.
std::filesystem::path shared_data();

/// A registered example: `name` is its file stem ("01_pixels"), `title` a line for the gallery.
struct Example {
  const char* name;
  const char* title;
  void (*run)(Gallery& gallery);
};

/// Registers an example (used by TESSERA_EXAMPLE at static-initialization time); returns a dummy.
int register_example(const Example& example);
/// Every registered example, sorted by name (so by number).
std::vector<Example> all_examples();
/// Runs examples whose name starts with one of `prefixes` (all when empty) into `dir`, and writes index.html.
/// Returns the number of pictures written.
size_t run_examples(const std::filesystem::path& dir, const std::vector<std::string>& prefixes = {});

}  // namespace tessera::examples

/// Defines and registers an example: TESSERA_EXAMPLE(ex01_pixels, "01_pixels", "The pink pixel") { ...gallery... }
#define TESSERA_EXAMPLE(id, name, title)                                                          \
  static void id(::tessera::examples::Gallery& gallery);                                         \
  [[maybe_unused]] static const int id##_registered =                                            \
      ::tessera::examples::register_example({name, title, &id});                                 \
  static void id([[maybe_unused]] ::tessera::examples::Gallery& gallery)
