#include "tessera/farm/frames.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <string>

#include "tessera/core/error.hpp"
#include "tessera/core/parse.hpp"
#include "tessera/image/image_io.hpp"

namespace tessera {

namespace fs = std::filesystem;

FrameRange parse_frame_range(std::string_view text, std::string_view what) {
  const auto parts = split(text, ':');
  if (parts.size() > 2)
    throw InvalidInput(fmt::format("{}: expected frames A:B or a frame N, got '{}'", what, printable(text)));
  const auto frame = [&](std::string_view part) {
    const long long f = parse_int(part, what);
    if (f < 0 || f > 10'000'000)
      throw InvalidInput(fmt::format("{}: expected frame numbers in [0, 10000000], got {}", what, f));
    return int(f);
  };
  const FrameRange range{frame(parts.front()), frame(parts.back())};
  if (range.last < range.first)
    throw InvalidInput(fmt::format("{}: the last frame {} comes before the first {}", what, range.last, range.first));
  return range;
}

TileSpec parse_tile(std::string_view text, std::string_view what) {
  const auto parts = split(text, '/');
  if (parts.size() != 2)
    throw InvalidInput(fmt::format("{}: expected K/N (tile K of N, K from 0), got '{}'", what, printable(text)));
  const long long k = parse_int(parts[0], what), n = parse_int(parts[1], what);
  if (n < 1 || n > 4096 || k < 0 || k >= n)
    throw InvalidInput(fmt::format("{}: expected 0 <= K < N <= 4096 in K/N, got {}/{}", what, k, n));
  return {int(k), int(n)};
}

PixelRect tile_rect(TileSpec tile, int width, int height) {
  if (height < tile.count)
    throw InvalidInput(fmt::format("{} tiles of rows do not fit a frame {} rows high", tile.count, height));
  const auto row = [&](int k) { return int(int64_t(k) * height / tile.count); };
  return {0, row(tile.index), width, row(tile.index + 1)};
}

fs::path tile_file(const fs::path& frame_file, TileSpec tile) {
  if (tile.count == 1) return frame_file;
  return frame_file.parent_path() / fmt::format("{}.tile-{}-of-{}{}", frame_file.stem().string(), tile.index,
                                                tile.count, frame_file.extension().string());
}

void check_lossless_image_path(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext == ".jpg" || ext == ".jpeg")
    throw InvalidInput(fmt::format("'{}': tiles need a lossless format (.png, .pfm, .hdr, .ppm, .bmp, .tga), not JPEG",
                                   printable(path.string(), 1024)));
}

void assemble_tiles(const fs::path& frame_file, int tile_count) {
  check_lossless_image_path(frame_file);
  if (tile_count < 1 || tile_count > 4096)
    throw InvalidInput(fmt::format("assemble: expected 1 to 4096 tiles, got {}", tile_count));
  if (tile_count == 1) return;  // the one tile is the frame
  // Tiles are read as floats (8-bit values v / 255, which write back to v) and the frame is written without alpha,
  // as a render writes it: the frame file's bytes are the unsplit render's.
  std::vector<ImageRGBA> tiles;
  int height = 0;
  for (int k = 0; k < tile_count; ++k) {
    const fs::path file = tile_file(frame_file, {k, tile_count});
    if (!fs::exists(file))
      throw IoError(fmt::format("'{}': tile {} of {} is missing", printable(file.string(), 1024), k, tile_count));
    tiles.push_back(read_image(file));
    if (tiles.back().width() != tiles.front().width())
      throw InvalidInput(fmt::format("'{}': the tile is {} pixels wide, tile 0 is {}", printable(file.string(), 1024),
                                     tiles.back().width(), tiles.front().width()));
    height += tiles.back().height();
  }
  const int width = tiles.front().width();
  for (int k = 0; k < tile_count; ++k) {
    const PixelRect rect = tile_rect({k, tile_count}, width, height);
    if (rect.y1 - rect.y0 != tiles[size_t(k)].height())
      throw InvalidInput(fmt::format("'{}': the tile has {} rows, tile {} of {} of a {}-row frame has {}",
                                     printable(tile_file(frame_file, {k, tile_count}).string(), 1024),
                                     tiles[size_t(k)].height(), k, tile_count, height, rect.y1 - rect.y0));
  }
  ImageRGB frame(width, height);
  int y = 0;
  for (const ImageRGBA& tile : tiles)
    for (int ty = 0; ty < tile.height(); ++ty, ++y)
      for (int x = 0; x < width; ++x) frame(x, y) = glm::vec3(tile(x, ty));
  write_image(frame_file, frame);
}

}  // namespace tessera
