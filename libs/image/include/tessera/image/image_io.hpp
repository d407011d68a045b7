#pragma once
// Image files: read PNG/JPG/BMP/TGA/HDR/PPM/PFM, write PNG/PPM/PFM/HDR/JPG (the extension picks the format).
//
// Renderers work in linear float RGB. 8-bit output clamps to [0, 1] and rounds, without gamma by default (as OpenGL
// and Processing); WriteOptions::srgb applies the sRGB transfer curve first. Every write is atomic (a temporary file
// renamed on success), so a failure never leaves a partial file. Errors are IoError (cannot open/write) or
// InvalidInput (malformed file, unknown extension), naming the file.
#include <filesystem>

#include "tessera/image/image.hpp"

namespace tessera {

/// How float pixels become 8-bit file values.
struct WriteOptions {
  bool srgb = false;      ///< encode with the sRGB curve instead of writing linear values
  int jpeg_quality = 95;  ///< 1..100, JPG only
};

/// Reads an image file as linear float RGBA. 8-bit files map v -> v/255 (no gamma decoding, the inverse of the
/// default write); HDR and PFM keep their float values. Gray images are expanded to RGB; missing alpha is 1.
ImageRGBA read_image(const std::filesystem::path& path);

/// Writes float RGB to PNG, PPM (P6), PFM, HDR or JPG by extension.
void write_image(const std::filesystem::path& path, const ImageRGB& image, const WriteOptions& options = {});
/// Writes float RGBA (PNG keeps alpha; the other formats drop it).
void write_image(const std::filesystem::path& path, const ImageRGBA& image, const WriteOptions& options = {});
/// Writes 8-bit RGBA (PNG, PPM, JPG; PFM/HDR convert to float).
void write_image(const std::filesystem::path& path, const ImageRGBA8& image, const WriteOptions& options = {});

/// Writes a one-channel float image as a grayscale PFM ("Pf"), e.g. a depth buffer.
void write_pfm(const std::filesystem::path& path, const DepthImage& image);
/// Reads a one-channel ("Pf") or three-channel ("PF") PFM; three channels are averaged to one.
DepthImage read_pfm_gray(const std::filesystem::path& path);

/// Converts linear float to 8-bit: clamp to [0, 1], optional sRGB encoding, round to nearest.
ImageRGBA8 to_rgba8(const ImageRGB& image, bool srgb = false);
ImageRGBA8 to_rgba8(const ImageRGBA& image, bool srgb = false);
/// Converts 8-bit to linear float (v/255, or sRGB-decoded when srgb).
ImageRGBA to_float(const ImageRGBA8& image, bool srgb = false);
/// Drops alpha.
ImageRGB to_rgb(const ImageRGBA& image);

}  // namespace tessera
