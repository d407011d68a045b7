#pragma once
// Palette quantization for GIF output (private to the image module; its tests reach it through src/): choosing at
// most 256 colors for a frame of 8-bit RGB pixels, and mapping the frame onto them with optional Floyd-Steinberg
// dithering. docs/image.md, "Animation output", describes the method.
#include <cstdint>
#include <glm/glm.hpp>
#include <optional>
#include <span>
#include <vector>

namespace tessera::detail {

using Rgb8 = glm::u8vec3;

/// A color as 0xRRGGBB (the order distinct_colors sorts by).
inline uint32_t pack_rgb(Rgb8 c) { return uint32_t(c.x) << 16 | uint32_t(c.y) << 8 | c.z; }

/// The distinct colors of `pixels` in increasing order of 0xRRGGBB when there are at most `limit` of them, else
/// nullopt (stops reading at the first color over the limit).
std::optional<std::vector<Rgb8>> distinct_colors(std::span<const Rgb8> pixels, int limit = 256);

/// A palette of at most `max_colors` (1..256) colors for `pixels`: the distinct colors themselves when there are
/// that few (every pixel is then exact), else median cut (Heckbert 1982) over a histogram of 5 bits per channel,
/// splitting the box with the largest squared error along its axis of largest variance at the cut that minimizes the
/// two halves' squared error (Wan, Wong and Prusinkiewicz 1988); each color is the mean of its box's pixels.
std::vector<Rgb8> quantize_palette(std::span<const Rgb8> pixels, int max_colors = 256);

/// quantize_palette's median cut alone, for a caller that already knows `pixels` hold more than `max_colors` colors
/// (1..256).
std::vector<Rgb8> median_cut_palette(std::span<const Rgb8> pixels, int max_colors = 256);

/// Nearest palette color (squared RGB distance, ties to the lower index), exact and fast: the RGB cube is cut into
/// 16^3 cells and each cell lazily keeps the candidates that can be nearest to a point inside it (entries whose
/// distance to the cell is at most the smallest distance to its farthest corner; Heckbert's locally sorted search).
class PaletteMapper {
 public:
  /// `palette` must hold 1..256 colors.
  explicit PaletteMapper(std::vector<Rgb8> palette);
  const std::vector<Rgb8>& palette() const { return palette_; }
  /// The index of the palette color nearest to (r, g, b), each 0..255.
  uint8_t nearest(int r, int g, int b);

 private:
  struct Candidate {
    int32_t cell_distance;  // squared distance from the cell to the color
    Rgb8 color;
    uint8_t index;
  };
  void build_cell(int cell);

  std::vector<Rgb8> palette_;
  std::vector<int32_t> cell_start_;    // per cell: its first candidate, -1 = not built yet
  std::vector<uint16_t> cell_count_;   // per cell: its number of candidates
  std::vector<Candidate> candidates_;  // per built cell, by increasing cell distance
};

/// Maps `pixels` (width x height, rows from the top) to palette indices in `out`: each pixel to its nearest color, or
/// with Floyd-Steinberg error diffusion (7/16, 3/16, 5/16, 1/16, serpentine rows, values clamped to [0, 255] before
/// choosing, the error passed on damped where it exceeds a multiple of the palette's mean error) when `dither`. A pixel
/// whose color is in the palette and receives no error maps to it exactly, so a frame of palette colors is reproduced
/// exactly either way.
void map_to_palette(std::span<const Rgb8> pixels, int width, int height, PaletteMapper& mapper, bool dither,
                    std::span<uint8_t> out);

}  // namespace tessera::detail
