#pragma once
// Image files: read PNG/JPG/BMP/TGA/HDR/PPM/PGM/PFM, write PNG/PPM/PFM/HDR/JPG/BMP/TGA (the extension picks the
// format, case-insensitively). Row 0 of every Image is the top row, whatever order the file stores rows in (PFM
// stores the bottom row first). docs/image.md has the formats table.
//
// Renderers work in linear float RGB. 8-bit output clamps to [0, 1] and rounds, without gamma by default (as OpenGL
// and Processing); WriteOptions::srgb applies the sRGB transfer curve first. Every write is atomic (a temporary file
// renamed on success), so a failure never leaves a partial file. Errors are IoError (cannot open/write) or
// InvalidInput (malformed file, unknown extension), naming the file.
#include <filesystem>
#include <string_view>
#include <variant>

#include "tessera/image/image.hpp"

namespace tessera {

/// Reading refuses images with more pixels than this (2^28, e.g. 16384 x 16384) before allocating anything, so a
/// hostile header cannot ask for gigabytes.
inline constexpr long long kMaxReadPixels = 1LL << 28;

/// How float pixels become 8-bit file values.
struct WriteOptions {
  bool srgb = false;      ///< encode with the sRGB curve instead of writing linear values
  int jpeg_quality = 95;  ///< 1..100, JPG only
};

/// Reads an image file as linear float RGBA. 8-bit files map v -> v/255 (no gamma decoding, the inverse of the
/// default write), 16-bit PNG and PPM v -> v/maxval; HDR and PFM keep their float values. Gray images are expanded
/// to RGB; missing alpha is 1. PPM/PGM: P2, P3, P5, P6 with maxval up to 65535. Throws IoError (cannot read) or
/// InvalidInput (unknown extension, malformed or truncated file, more than kMaxReadPixels), naming the file.
ImageRGBA read_image(const std::filesystem::path& path);
/// read_image on bytes already in memory: `name`'s extension picks the format and names the data in messages (for
/// data that does not come from a file, and for fuzzing).
ImageRGBA decode_image(std::string_view data, const std::filesystem::path& name);

/// An image in the precision of its file: 8-bit RGBA or float RGBA.
using FileImage = std::variant<ImageRGBA8, ImageRGBA>;
/// Reads an image file keeping 8-bit files 8-bit, for textures: 8-bit PNG, JPG, BMP, TGA and PPM/PGM with maxval
/// 255 give ImageRGBA8 with the file's values (to_float of it is read_image's image, bit for bit), without a float
/// image in between; 16-bit PNG and PPM, other maxvals, HDR and PFM give read_image's float image. The memory
/// budget is checked as in read_image with 4 bytes per pixel instead of 16 for the 8-bit image. Throws as read_image.
FileImage read_image_native(const std::filesystem::path& path);
/// read_image_native on bytes already in memory (as decode_image).
FileImage decode_image_native(std::string_view data, const std::filesystem::path& name);

/// Writes float RGB to PNG, PPM (P6), PFM, HDR, JPG, BMP or TGA by extension. Throws InvalidInput (unknown
/// extension, empty image) before creating anything, IoError when the file cannot be written.
void write_image(const std::filesystem::path& path, const ImageRGB& image, const WriteOptions& options = {});
/// Writes float RGBA (PNG and TGA keep alpha; the other formats drop it).
void write_image(const std::filesystem::path& path, const ImageRGBA& image, const WriteOptions& options = {});
/// Writes 8-bit RGBA as is (PNG and TGA keep alpha); PFM/HDR convert with to_float(image, options.srgb).
void write_image(const std::filesystem::path& path, const ImageRGBA8& image, const WriteOptions& options = {});

/// Writes a one-channel float image as a grayscale little-endian PFM ("Pf"), e.g. a depth buffer. Throws as
/// write_image.
void write_pfm(const std::filesystem::path& path, const DepthImage& image);
/// Reads a one-channel ("Pf") or three-channel ("PF") PFM; three channels are averaged to one. Throws as
/// read_image.
DepthImage read_pfm_gray(const std::filesystem::path& path);

/// Converts linear float to 8-bit: clamp to [0, 1] (NaN -> 0), optional sRGB encoding of RGB (never alpha), round
/// to nearest. RGB input gets alpha 255.
ImageRGBA8 to_rgba8(const ImageRGB& image, bool srgb = false);
ImageRGBA8 to_rgba8(const ImageRGBA& image, bool srgb = false);
/// Converts 8-bit to linear float (v/255, or sRGB-decoded RGB when srgb; alpha is always v/255).
ImageRGBA to_float(const ImageRGBA8& image, bool srgb = false);
/// Drops alpha; and the inverse, adding alpha 1.
ImageRGB to_rgb(const ImageRGBA& image);
ImageRGBA to_rgba(const ImageRGB& image);

}  // namespace tessera
