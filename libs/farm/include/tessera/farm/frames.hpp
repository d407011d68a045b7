#pragma once
// Frames and tiles of a render split across processes or machines (docs/farm.md): frame ranges, tiles of a frame,
// where each part's file goes, and stitching the tiles of a frame back into it.
#include <filesystem>
#include <string_view>

namespace tessera {

/// The frames first..last, both included.
struct FrameRange {
  int first = 0, last = 0;
  /// last - first + 1.
  int count() const { return last - first + 1; }
};

/// Parses "A:B" (frames A to B) or "N" (frame N), as --frames takes them. Throws InvalidInput naming `what` for
/// anything else, a negative frame or B < A.
FrameRange parse_frame_range(std::string_view text, std::string_view what);

/// Tile `index` of a frame split into `count` bands of rows (index from 0, as Slurm's array task ids).
struct TileSpec {
  int index = 0, count = 1;
};

/// Parses "K/N" with 0 <= K < N <= 4096, as --tile takes it. Throws InvalidInput naming `what` otherwise.
TileSpec parse_tile(std::string_view text, std::string_view what);

/// A rectangle of pixels, [x0, x1) x [y0, y1).
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

/// The pixels tile `tile` covers in a width x height frame: every column, rows [floor(K h / N), floor((K + 1) h / N)).
/// Throws InvalidInput when the frame has fewer rows than tiles.
PixelRect tile_rect(TileSpec tile, int width, int height);

/// Where tile K of N of `frame_file` goes: "<stem>.tile-K-of-N<ext>" beside it ("f_0007.png" ->
/// "f_0007.tile-2-of-8.png"); the frame file itself when N = 1 (the one tile is the frame).
std::filesystem::path tile_file(const std::filesystem::path& frame_file, TileSpec tile);

/// Stitches the `tile_count` tile files of `frame_file` (tile_file of K = 0..N-1, each the rows tile_rect gives) into
/// the frame and writes it atomically in the frame file's format (nothing to do for one tile). Lossless formats only:
/// the frame's bytes are those an unsplit render writes. Throws IoError naming a missing or unreadable tile,
/// InvalidInput for tiles whose sizes do not fit together or a lossy (JPEG) format.
void assemble_tiles(const std::filesystem::path& frame_file, int tile_count);

/// Refuses formats whose pixels do not survive a write and a read (JPEG): a tile must hold the frame's own values.
/// Throws InvalidInput naming `path`.
void check_lossless_image_path(const std::filesystem::path& path);

}  // namespace tessera
