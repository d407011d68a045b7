#pragma once
// Animation output: frames streamed, one at a time, to an animated GIF, a numbered image sequence or a video piped
// to ffmpeg; the path picks which. docs/image.md, "Animation output", says how each is encoded.
//
//   AnimationWriter writer("spin.gif", AnimationOptions{.fps = 30});
//   for (...) writer.add(frame);  // ImageRGB, ImageRGBA or ImageRGBA8, all of the first frame's size
//   writer.finish();              // the file appears here, complete
//
// Frames are float images converted to 8-bit exactly as write_image converts them: clamped to [0, 1], sRGB-encoded
// only when `srgb` is set (WriteOptions::srgb, the CLI's --srgb), rounded. Alpha is dropped except by RGBA PNG
// sequences. A GIF or video is written to a temporary file beside the target and renamed by finish(); a writer
// destroyed without finish() (an exception mid-animation) leaves nothing behind. Memory does not grow with the
// number of frames.
#include <filesystem>
#include <memory>

#include "tessera/image/image.hpp"

namespace tessera {

/// What the output path asks for.
enum class AnimationFormat {
  gif,       ///< "*.gif": an animated GIF (giflib)
  sequence,  ///< a file name with a run of '#' or a "%0Nd" ("frames/frame-####.png", "frame_%04d.png"), an existing
             ///< folder or a path ending in '/' (then "frame-0000.png", "frame-0001.png", ...): one image file per
             ///< frame, through write_image
  video,     ///< "*.mp4", "*.mov", "*.mkv" (H.264) or "*.webm" (VP9), encoded by ffmpeg found on PATH
};

/// How a GIF picks the palette (at most 256 colors) of each frame.
enum class GifPalette {
  automatic,  ///< the first frame's palette is the file's global table; a later frame uses it when it holds every
              ///< color of the frame (nothing is lost), else its own palette: flat-colored sketches share one
              ///< table, renderings get the best palette per frame
  per_frame,  ///< every frame quantized to its own palette (a local color table after the first frame)
  shared,     ///< every frame mapped to the first frame's palette (smallest file, no palette flicker; colors that
              ///< appear only later are approximated)
};

/// Options of an AnimationWriter; every field has a default.
struct AnimationOptions {
  double fps = 30;     ///< frames per second, > 0 (GIF: at most 50, its delays are whole centiseconds)
  bool srgb = false;   ///< encode 8-bit values with the sRGB curve (as WriteOptions::srgb)
  bool dither = true;  ///< GIF: Floyd-Steinberg error diffusion where a frame's colors are not all in its palette
  int loop = 0;        ///< GIF: 0 loops forever; n > 0 plays n more times after the first; -1 plays once
  GifPalette palette = GifPalette::automatic;  ///< GIF: how frames get their palettes
  int crf = -1;  ///< video: the encoder's constant-rate factor (lower is better); -1 = 20 for H.264, 32 for VP9
};

/// The format `path` asks for (see AnimationFormat). Throws InvalidInput for anything else, listing the choices.
AnimationFormat animation_format(const std::filesystem::path& path);

/// Processing's saveFrame naming: `pattern` with the run of '#' in its file name replaced by `frame`, zero-padded
/// to the run's width ("frame-####.png", 7 -> "frame-0007.png"; a wider number is written whole, 12345 ->
/// "frame-12345.png"); printf's "%0Nd" and "%d" work the same ("frame_%04d.png", 7 -> "frame_0007.png"). A file
/// name without either is returned unchanged. Throws InvalidInput for two or more such fields in the file name or a
/// negative frame.
std::filesystem::path numbered_frame_path(const std::filesystem::path& pattern, long long frame);

/// Streams frames to the animation `path` asks for (animation_format). Not copyable; movable (a moved-from writer may
/// only be destroyed or assigned to).
class AnimationWriter {
 public:
  /// Checks the path and options and starts the output: a GIF's temporary file, ffmpeg for a video, the folder of a
  /// sequence (created when missing). Throws InvalidInput (unknown format, bad options) or IoError (cannot create
  /// the output; for a video, ffmpeg not on PATH).
  explicit AnimationWriter(const std::filesystem::path& path, const AnimationOptions& options = {});
  /// Without finish(), removes the temporary file and stops ffmpeg: no GIF or video appears (sequence frames
  /// already written stay, each a complete file).
  ~AnimationWriter();
  AnimationWriter(AnimationWriter&&) noexcept;
  AnimationWriter& operator=(AnimationWriter&&) noexcept;

  /// Appends a frame. The first frame fixes the size; a frame of another size, an empty frame or a call after
  /// finish() throws InvalidInput. Throws IoError when writing fails (for a video: with ffmpeg's message) and
  /// MemoryBudgetError when the first frame's work buffers exceed the memory budget.
  void add(const ImageRGB& frame);
  void add(const ImageRGBA& frame);
  /// Appends an 8-bit frame (a sketch's canvas): its values are written as they are (`srgb` does not apply).
  void add(const ImageRGBA8& frame);

  /// Completes the output: writes the GIF's trailer or waits for ffmpeg, then renames the file into place. Throws
  /// InvalidInput when no frame was added, IoError when the output cannot be completed (ffmpeg's message included).
  void finish();

  /// Frames added so far.
  long long frames() const;
  /// The format chosen from the path.
  AnimationFormat format() const;
  /// The sequence's file name for frame i (numbered_frame_path of the pattern), or the GIF or video path.
  std::filesystem::path frame_path(long long i) const;

  /// A GIF frame's delay in centiseconds so that the average rate is `fps`: the first i frames last
  /// floor(100 i / fps) in total, so 30 fps gives 3, 3, 4, 3, 3, 4, ... (exposed for tests and documentation).
  static int gif_delay_cs(double fps, long long i);

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tessera
