#pragma once
// The examples' registry and the gallery they feed.
//
// Each numbered example (examples/NN_name.cpp) is a function that draws one or more pictures and hands them to a
// Gallery. The same function runs as its own program (a test) and inside `tessera gallery` / `tessera demo`.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "tessera/image/image.hpp"
#include "tessera/image/image_io.hpp"

namespace tessera::examples {

/// One picture of the gallery.
struct Picture {
  std::string file;     ///< file name inside the gallery folder, e.g. "01_pink_pixel.png"
  std::string caption;  ///< one sentence for index.html
};

/// Where the shared data sets (a folder with meshes/, volumes/, env/, textures/, bezier/) were looked for: the folder,
/// and what named it ("--data", "TESSERA_DATA", "./shared/data", ...; see locate_shared_data).
struct DataFolder {
  std::filesystem::path dir;  ///< empty when no candidate exists
  std::string source;         ///< what chose dir, for messages
};

/// Finds the shared data folder. The first given of `option` (tessera's --data), $TESSERA_DATA and
/// $TESSERA_SHARED_DATA is used as it is, existing or not (so a wrong setting is reported, not silently replaced);
/// without any, the first existing folder of: ./shared/data, ../shared/data, shared/data in the executable's folder or
/// any folder above it, and the folder configured at build time (CMake's TESSERA_SHARED_DATA). Returns an empty dir
/// when none exists.
DataFolder locate_shared_data(const std::filesystem::path& option = {});

/// The candidates locate_shared_data tries when neither the option nor an environment variable is given, in order,
/// with their sources (for messages and tests).
std::vector<DataFolder> default_data_folders();

/// Collects pictures into a folder; write_index() makes index.html with a caption per picture.
class Gallery {
 public:
  /// Creates the folder if needed. Throws IoError when it cannot. `data` is where data_file() looks; `write` is how
  /// add() encodes the pictures (WriteOptions::srgb: the sRGB curve on float pictures).
  explicit Gallery(std::filesystem::path dir, DataFolder data = locate_shared_data(), WriteOptions write = {});
  /// Writes an image (PNG, atomically) under `file` and records its caption.
  void add(const std::string& file, const ImageRGB& image, const std::string& caption);
  void add(const std::string& file, const ImageRGBA8& image, const std::string& caption);
  /// Records a file the example wrote itself (e.g. an SVG) under `file` in dir().
  void add_file(const std::string& file, const std::string& caption);
  /// The folder pictures go to.
  const std::filesystem::path& dir() const { return dir_; }
  /// A file of the shared data (`relative`, e.g. "meshes/bunny/bun_zipper_res2.ply"): its path when it exists;
  /// otherwise nullopt, after a warning on stderr naming the missing file, where the data was looked for and the
  /// stand-in the example draws instead (`stand_in`), counted in stand_ins(). The example's caption must say so too
  /// (stand_in_caption).
  std::optional<std::filesystem::path> data_file(const std::string& relative, const std::string& stand_in);
  /// The number of data files that were missing (each drawn as a stand-in).
  size_t stand_ins() const { return stand_ins_; }
  /// Everything added so far, in order.
  const std::vector<Picture>& pictures() const { return pictures_; }
  /// Writes dir()/index.html listing every picture with its caption, grouped by example title.
  void write_index(const std::string& title) const;
  /// Starts a new section (an example's title) for the pictures that follow.
  void section(const std::string& title);

 private:
  std::filesystem::path dir_;
  DataFolder data_;
  WriteOptions write_;
  size_t stand_ins_ = 0;
  std::vector<Picture> pictures_;
  std::vector<std::pair<size_t, std::string>> sections_;  // (first picture index, title)
};

/// Copies `tile` into `sheet` with its top-left corner at (x0, y0), clipped to the sheet (contact sheets of panels).
void paste(ImageRGB& sheet, const ImageRGB& tile, int x0, int y0 = 0);
/// Panels placed left to right, top-aligned, on a white sheet as tall as the tallest. Precondition: not empty.
ImageRGB side_by_side(const std::vector<ImageRGB>& panels);

/// The caption of a picture drawn with a stand-in for missing shared data: "STAND-IN (shared data not found; drawn
/// instead of `real`: `what`): " + caption.
std::string stand_in_caption(const std::string& what, const std::string& real, const std::string& caption);

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
/// What run_examples did.
struct RunSummary {
  size_t pictures = 0;           ///< pictures written
  size_t stand_ins = 0;          ///< shared data files that were missing (stand-ins drawn)
  std::vector<Picture> written;  ///< the pictures, in order (files in the run's folder)
};

/// Which examples run_examples runs, and how.
struct RunOptions {
  std::vector<std::string> prefixes;       ///< run examples whose name starts with one of these (all when empty)
  DataFolder data = locate_shared_data();  ///< where the shared data is read from
  WriteOptions write;                      ///< how pictures are encoded (see Gallery)
};

/// Runs the examples `options` selects into `dir` and writes index.html.
RunSummary run_examples(const std::filesystem::path& dir, const RunOptions& options = {});

/// How far a picture may be from its reviewed reference (docs/gallery) and still pass. The examples render the same
/// bytes for any thread count; the slack is for other CPUs' vector paths and compilers. A picture fails when more than
/// `pixels` of its pixels differ by more than `levels` in a channel (a shape moved by a pixel or a changed color), or
/// when its PSNR is below `min_psnr` (a small change everywhere, e.g. every color 2 levels darker).
struct Tolerance {
  int levels = 3;          ///< a channel within this many 8-bit levels of the reference counts as equal
  double pixels = 5e-5;    ///< fraction of the pixels that may differ by more than `levels` (0.00005: 6 of 360x360)
  double min_psnr = 45.0;  ///< dB over the four channels (45 dB: an RMS difference of 1.4 levels)
};

/// The outcome of comparing a picture with its reference.
struct Comparison {
  bool passed = false;
  std::string message;  ///< the measured figures against the tolerance, or why the images cannot be compared
};

/// Compares `picture` with `reference` (image/metrics.hpp: count_differing_pixels, max_abs_difference, psnr). Images
/// of different sizes fail.
Comparison compare_picture(const ImageRGBA8& picture, const ImageRGBA8& reference, const Tolerance& tolerance = {});

/// Whether a picture was drawn with a stand-in for missing shared data (its caption is a stand_in_caption): such a
/// picture has no reference to meet.
bool is_stand_in(const Picture& picture);

}  // namespace tessera::examples

/// Defines and registers an example: TESSERA_EXAMPLE(ex01_pixels, "01_pixels", "The pink pixel") { ...gallery... }
#define TESSERA_EXAMPLE(id, name, title)                                                                         \
  static void id(::tessera::examples::Gallery& gallery);                                                         \
  [[maybe_unused]] static const int id##_registered = ::tessera::examples::register_example({name, title, &id}); \
  static void id([[maybe_unused]] ::tessera::examples::Gallery& gallery)
