#include "tessera/image/image_io.hpp"

#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include <algorithm>
#include <cctype>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "jpeg_decode.hpp"
#include "pixel_budget.hpp"
#include "png_encode.hpp"
#include "tessera/color/srgb.hpp"
#include "tessera/core/atomic_file.hpp"
#include "tessera/core/error.hpp"
#include "tessera/core/memory_budget.hpp"
#include "tessera/core/parse.hpp"

namespace tessera {

void detail::check_pixel_count(const std::string& name, long long width, long long height, uint64_t bytes_per_pixel) {
  if (width < 1 || height < 1 || width > kMaxReadPixels / height)
    throw InvalidInput(
        fmt::format("'{}': image size {}x{} is invalid or larger than {} pixels", name, width, height, kMaxReadPixels));
  MemoryBudget::check(saturating_product({uint64_t(width), uint64_t(height), bytes_per_pixel}),
                      fmt::format("'{}': decoding {}x{} pixels", name, width, height));
}

namespace {

using detail::check_pixel_count;

enum class Format { png, jpg, bmp, tga, hdr, ppm, pfm };

struct FormatEntry {
  std::string_view extension;
  Format format;
  bool writable;  // every entry is readable
};

constexpr FormatEntry formats[] = {
    {".png", Format::png, true}, {".jpg", Format::jpg, true},  {".jpeg", Format::jpg, true},
    {".bmp", Format::bmp, true}, {".tga", Format::tga, true},  {".hdr", Format::hdr, true},
    {".ppm", Format::ppm, true}, {".pgm", Format::ppm, false}, {".pnm", Format::ppm, false},
    {".pfm", Format::pfm, true},
};

std::string name_of(const std::filesystem::path& path) { return path.string(); }

// The format an extension names; throws InvalidInput listing what is supported for reading or writing.
Format format_of(const std::filesystem::path& path, bool writing) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  std::string supported;
  for (const FormatEntry& entry : formats) {
    if (writing && !entry.writable) continue;
    if (entry.extension == ext) return entry.format;
    supported += (supported.empty() ? "" : ", ") + std::string(entry.extension);
  }
  throw InvalidInput(fmt::format("'{}': unknown image extension '{}' ({} supports {})", name_of(path), ext,
                                 writing ? "writing" : "reading", supported));
}

// Decoded pixels before they become RGBA: `channels` (1 or 3) floats per pixel, top row first; a pixel's value is
// values / divisor (Netpbm samples are kept as integers with divisor = maxval, PFM values with divisor 1).
struct Decoded {
  int width = 0, height = 0, channels = 0;
  float divisor = 1.f;
  std::vector<float> values;
};

// The pixels as RGBA: gray expanded to RGB, alpha `opaque`.
template <class Pixel, class Convert>
Image<Pixel> expand_rgba(const Decoded& d, Convert convert, typename Pixel::value_type opaque) {
  Image<Pixel> image(d.width, d.height);
  auto pixels = image.pixels();
  for (size_t i = 0; i < pixels.size(); ++i) {
    const float* v = &d.values[i * size_t(d.channels)];
    const int g = d.channels == 1 ? 0 : 1, b = d.channels == 1 ? 0 : 2;
    pixels[i] = Pixel(convert(v[0]), convert(v[g]), convert(v[b]), opaque);
  }
  return image;
}

ImageRGBA to_rgba_image(const Decoded& d) {
  return expand_rgba<glm::vec4>(
      d, [&](float v) { return v / d.divisor; }, 1.f);
}

// Netpbm samples of maxval 255 as they are.
ImageRGBA8 to_rgba8_image(const Decoded& d) {
  return expand_rgba<glm::u8vec4>(
      d, [](float v) { return uint8_t(v); }, uint8_t(255));
}

// Reads the whitespace-separated header of the Netpbm formats and PFM, tracking byte offsets for messages.
class HeaderReader {
 public:
  HeaderReader(std::string_view data, std::string name, bool comments)
      : data_(data), name_(std::move(name)), comments_(comments) {}

  size_t offset() const { return pos_; }

  [[noreturn]] void fail(size_t offset, const std::string& what) const {
    throw InvalidInput(located(at_byte(name_, (long long)offset), what));
  }

  // The next token; `what` names it in the error when the data ends first.
  std::string_view token(std::string_view what) {
    skip_space();
    token_start_ = pos_;
    while (pos_ < data_.size() && !std::isspace((unsigned char)data_[pos_])) ++pos_;
    if (token_start_ == pos_) fail(pos_, fmt::format("truncated: expected {}", what));
    return data_.substr(token_start_, pos_ - token_start_);
  }

  // The next token as an integer in [lo, hi].
  long long integer(std::string_view what, long long lo, long long hi) {
    const std::string_view text = token(what);
    long long value = 0;
    try {
      value = parse_int(text, what);
    } catch (const InvalidInput& e) {
      fail(token_start_, e.what());
    }
    if (value < lo || value > hi) fail(token_start_, fmt::format("{} {} is outside [{}, {}]", what, value, lo, hi));
    return value;
  }

  // The next token as a finite number.
  double real(std::string_view what) {
    const std::string_view text = token(what);
    try {
      return parse_double(text, what);
    } catch (const InvalidInput& e) {
      fail(token_start_, e.what());
    }
  }

  // Where the last token began.
  size_t token_start() const { return token_start_; }

  // The header ends with exactly one white-space byte before binary data.
  void end_of_header() {
    if (pos_ >= data_.size() || !std::isspace((unsigned char)data_[pos_]))
      fail(pos_, "expected one white-space byte after the header");
    ++pos_;
  }

  // Throws unless `bytes` more bytes follow the current offset; `what` names them.
  void require(unsigned long long bytes, std::string_view what) const {
    const size_t left = data_.size() - pos_;
    if (bytes > left)
      fail(data_.size(), fmt::format("truncated: {} needs {} bytes from byte offset {}, the file ends after {}", what,
                                     bytes, pos_, left));
  }

 private:
  void skip_space() {
    while (pos_ < data_.size()) {
      const char c = data_[pos_];
      if (std::isspace((unsigned char)c)) {
        ++pos_;
      } else if (comments_ && c == '#') {
        while (pos_ < data_.size() && data_[pos_] != '\n' && data_[pos_] != '\r') ++pos_;
      } else {
        break;
      }
    }
  }

  std::string_view data_;
  std::string name_;
  bool comments_;
  size_t pos_ = 0;
  size_t token_start_ = 0;
};

// PPM/PGM: P2/P5 gray and P3/P6 RGB, ASCII or binary, maxval 1..65535 (16-bit samples big-endian). `keep_8bit`:
// the budget counts an 8-bit image for maxval 255.
Decoded read_netpbm(std::string_view data, const std::string& name, bool keep_8bit) {
  HeaderReader in(data, name, true);
  const std::string_view magic = in.token("the magic number P2, P3, P5 or P6");
  if (magic != "P2" && magic != "P3" && magic != "P5" && magic != "P6")
    in.fail(0, fmt::format("expected the magic number P2, P3, P5 or P6, got '{}'", printable(magic, 8)));
  Decoded d;
  d.channels = magic == "P2" || magic == "P5" ? 1 : 3;
  const bool binary = magic == "P5" || magic == "P6";
  d.width = int(in.integer("width", 1, INT_MAX));
  d.height = int(in.integer("height", 1, INT_MAX));
  const long long maxval = in.integer("maxval", 1, 65535);
  const size_t image_bytes = keep_8bit && maxval == 255 ? sizeof(ImageRGBA8::Pixel) : sizeof(ImageRGBA::Pixel);
  check_pixel_count(name, d.width, d.height, sizeof(float) * d.channels + image_bytes);
  const unsigned long long count = (unsigned long long)d.width * (unsigned long long)d.height * d.channels;
  d.divisor = float(maxval);
  if (binary) {
    in.end_of_header();
    const int bytes = maxval > 255 ? 2 : 1;
    in.require(count * bytes, "the pixel data");
    d.values.resize(count);
    const auto* p = reinterpret_cast<const unsigned char*>(data.data() + in.offset());
    for (size_t i = 0; i < count; ++i) {
      const unsigned v = bytes == 2 ? (unsigned(p[2 * i]) << 8 | p[2 * i + 1]) : p[i];
      if (v > maxval) in.fail(in.offset() + i * bytes, fmt::format("sample {} exceeds maxval {}", v, maxval));
      d.values[i] = float(v);
    }
  } else {
    // Every ASCII sample takes at least one byte: a cheap bound before allocating.
    in.require(count, "the ASCII pixel data");
    d.values.resize(count);
    for (size_t i = 0; i < count; ++i) d.values[i] = float(in.integer("a sample", 0, maxval));
  }
  return d;
}

float float_from_bytes(const unsigned char* p, bool little_endian) {
  const uint32_t bits = little_endian
                            ? uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24
                            : uint32_t(p[3]) | uint32_t(p[2]) << 8 | uint32_t(p[1]) << 16 | uint32_t(p[0]) << 24;
  float value;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

// PFM: "PF" (RGB) or "Pf" (gray), width height, scale (negative = little endian), then float rows bottom first.
// Sample values are returned as stored; the magnitude of the scale is not applied. A NaN or infinite sample is
// refused with its pixel (top row 0, as the image is indexed) and byte offset, as the volume readers refuse such
// voxels: it would reach pictures, textures and statistics as NaN. (Radiance HDR cannot store one: RGBE gives at
// most 255 x 2^119.)
Decoded read_pfm_data(std::string_view data, const std::string& name) {
  HeaderReader in(data, name, false);
  const std::string_view magic = in.token("the magic number PF or Pf");
  if (magic != "PF" && magic != "Pf") in.fail(0, fmt::format("expected PF or Pf, got '{}'", printable(magic, 8)));
  Decoded d;
  d.channels = magic == "PF" ? 3 : 1;
  d.width = int(in.integer("width", 1, INT_MAX));
  d.height = int(in.integer("height", 1, INT_MAX));
  check_pixel_count(name, d.width, d.height, sizeof(float) * d.channels + sizeof(ImageRGBA::Pixel));
  const double scale = in.real("the scale (negative for little endian)");
  if (scale == 0.0) in.fail(in.token_start(), "the scale must be nonzero (its sign gives the byte order)");
  in.end_of_header();
  const size_t row_values = size_t(d.width) * size_t(d.channels);
  in.require(4ull * row_values * size_t(d.height), "the pixel data");
  d.values.resize(row_values * size_t(d.height));
  const auto* first = reinterpret_cast<const unsigned char*>(data.data() + in.offset());
  const auto* p = first;
  for (int file_row = 0; file_row < d.height; ++file_row) {
    const int y = d.height - 1 - file_row;
    float* out = &d.values[size_t(y) * row_values];
    for (size_t i = 0; i < row_values; ++i) {
      out[i] = float_from_bytes(p + 4 * i, scale < 0);
      if (!std::isfinite(out[i]))
        in.fail(in.offset() + size_t(p + 4 * i - first),
                fmt::format("pixel ({}, {}){} is {}: PFM samples must be finite", i / size_t(d.channels), y,
                            d.channels == 3 ? fmt::format(" channel {}", "rgb"[i % 3]) : "", out[i]));
    }
    p += 4 * row_values;
  }
  return d;
}

struct StbFree {
  void operator()(void* p) const { stbi_image_free(p); }
};

// Interleaved RGBA samples divided by `divisor` (a division, so v/255 matches to_float exactly).
template <class Sample>
ImageRGBA from_interleaved_rgba(const Sample* p, int width, int height, float divisor) {
  ImageRGBA image(width, height);
  auto pixels = image.pixels();
  for (size_t i = 0; i < pixels.size(); ++i)
    pixels[i] = glm::vec4(float(p[4 * i]), float(p[4 * i + 1]), float(p[4 * i + 2]), float(p[4 * i + 3])) / divisor;
  return image;
}

// Walks a PNG file's chunks and refuses one whose declared length runs past the end of the file, before stb_image
// (which would first grow its buffer to the declared length: up to 2 GiB for a chunk in a 100-byte file).
void check_png_chunks(std::string_view data, const std::string& name) {
  constexpr std::string_view signature("\x89PNG\r\n\x1A\n", 8);
  if (!data.starts_with(signature)) return;
  const auto byte = [&](size_t i) { return uint32_t(static_cast<unsigned char>(data[i])); };
  for (size_t at = signature.size(); at + 8 <= data.size();) {
    const uint64_t length = byte(at) << 24 | byte(at + 1) << 16 | byte(at + 2) << 8 | byte(at + 3);
    const std::string_view type = data.substr(at + 4, 4);
    if (length + 12 > data.size() - at)
      throw InvalidInput(
          fmt::format("'{}': PNG chunk '{}' at byte {} declares {} bytes of data, but the file ends {} "
                      "bytes later",
                      name, printable(type), at, length, data.size() - at));
    if (type == "IEND") return;
    at += 12 + length;
  }
}

// PNG, BMP, TGA, HDR through stb_image: 16-bit files scaled to [0, 1], HDR as stored, 8-bit files scaled to
// [0, 1] or, with `keep_8bit`, copied as they are.
FileImage read_stb(std::string_view data, const std::string& name, bool keep_8bit) {
  if (data.size() > size_t(INT_MAX)) throw InvalidInput(fmt::format("'{}': file is larger than 2 GiB", name));
  check_png_chunks(data, name);
  const auto* bytes = reinterpret_cast<const stbi_uc*>(data.data());
  const int size = int(data.size());
  int width = 0, height = 0, channels = 0;
  const auto failed = [&] {
    const std::string_view reason = stbi_failure_reason() ? stbi_failure_reason() : "unknown error";
    if (reason == "outofmem")
      return InvalidInput(
          fmt::format("'{}': cannot decode image: it needs a buffer larger than the memory budget of {}", name,
                      format_bytes(MemoryBudget::bytes())));
    return InvalidInput(fmt::format("'{}': cannot decode image: {}", name, reason));
  };
  if (!stbi_info_from_memory(bytes, size, &width, &height, &channels)) throw failed();
  const bool hdr = stbi_is_hdr_from_memory(bytes, size), wide = !hdr && stbi_is_16_bit_from_memory(bytes, size);
  keep_8bit = keep_8bit && !hdr && !wide;
  check_pixel_count(name, width, height,
                    4 * (hdr    ? sizeof(float)
                         : wide ? 2
                                : 1) +
                        (keep_8bit ? sizeof(ImageRGBA8::Pixel) : sizeof(ImageRGBA::Pixel)));
  if (hdr) {
    std::unique_ptr<float, StbFree> p(stbi_loadf_from_memory(bytes, size, &width, &height, &channels, 4));
    if (!p) throw failed();
    return from_interleaved_rgba(p.get(), width, height, 1.f);
  }
  if (wide) {
    std::unique_ptr<stbi_us, StbFree> p(stbi_load_16_from_memory(bytes, size, &width, &height, &channels, 4));
    if (!p) throw failed();
    return from_interleaved_rgba(p.get(), width, height, 65535.f);
  }
  std::unique_ptr<stbi_uc, StbFree> p(stbi_load_from_memory(bytes, size, &width, &height, &channels, 4));
  if (!p) throw failed();
  if (!keep_8bit) return from_interleaved_rgba(p.get(), width, height, 255.f);
  ImageRGBA8 image(width, height);
  std::memcpy(image.pixels().data(), p.get(), image.pixels().size_bytes());
  return image;
}

// Every reader; `keep_8bit` keeps 8-bit files 8-bit (read_image_native).
FileImage decode(std::string_view data, const std::filesystem::path& path, bool keep_8bit) {
  // stb_image recognizes files by their content, so the extension names a format only where the content has no
  // signature. JPEG and binary Netpbm files go to their readers by signature whatever they are called (Debian's stb
  // decoded a 16-bit Netpbm file misnamed .png into half the buffer it returned, a heap overflow found by
  // fuzz_image_formats; its JPEG decoder corrupts its own tables on a DHT of more than 256 codes).
  const bool netpbm = data.size() >= 2 && data[0] == 'P' && (data[1] == '5' || data[1] == '6');
  const Format format = netpbm ? Format::ppm : format_of(path, false);
  const std::string name = name_of(path);
  if (detail::is_jpeg(data)) return detail::decode_jpeg(data, name, keep_8bit);
  switch (format) {
    case Format::ppm: {
      const Decoded d = read_netpbm(data, name, keep_8bit);
      if (keep_8bit && d.divisor == 255.f) return to_rgba8_image(d);
      return to_rgba_image(d);
    }
    case Format::pfm:
      return to_rgba_image(read_pfm_data(data, name));
    default:
      return read_stb(data, name, keep_8bit);
  }
}

// ---- writing ----

void stb_sink(void* context, void* data, int size) {
  static_cast<std::ostream*>(context)->write(static_cast<const char*>(data), size);
}

void check_writable(const std::filesystem::path& path, int width, int height, const WriteOptions& options) {
  if (width < 1 || height < 1)
    throw InvalidInput(fmt::format("'{}': cannot write an empty {}x{} image", name_of(path), width, height));
  if (options.jpeg_quality < 1 || options.jpeg_quality > 100)
    throw InvalidInput(fmt::format("'{}': JPEG quality {} is outside [1, 100]", name_of(path), options.jpeg_quality));
}

void write_float_le(std::ostream& out, float value) {
  uint32_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  const char bytes[4] = {char(bits & 0xff), char(bits >> 8 & 0xff), char(bits >> 16 & 0xff), char(bits >> 24)};
  out.write(bytes, 4);
}

// A result that is not finite is an error, never a file: PFM and HDR would store NaN or infinity (or garbage), and
// the readers refuse them. `values` holds `channels` floats per pixel, top row first.
void check_finite(const std::filesystem::path& path, const std::vector<float>& values, int width, int channels) {
  const auto bad = std::find_if(values.begin(), values.end(), [](float v) { return !std::isfinite(v); });
  if (bad == values.end()) return;
  const size_t i = size_t(bad - values.begin()), pixel = i / size_t(channels);
  const std::string channel = channels == 1 ? "" : fmt::format(" channel {}", "rgb"[i % size_t(channels)]);
  throw InvalidInput(fmt::format("'{}': pixel ({}, {}){} is {}: refusing to write a value that is not finite",
                                 name_of(path), pixel % size_t(width), pixel / size_t(width), channel, *bad));
}

// PFM body: `values` holds `channels` floats per pixel, top row first; the file gets the bottom row first.
void write_pfm_stream(std::ostream& out, int width, int height, int channels, const std::vector<float>& values) {
  out << (channels == 3 ? "PF" : "Pf") << '\n' << width << ' ' << height << "\n-1\n";
  const size_t row_values = size_t(width) * size_t(channels);
  for (int y = height - 1; y >= 0; --y)
    for (size_t i = 0; i < row_values; ++i) write_float_le(out, values[size_t(y) * row_values + i]);
}

// 8-bit formats (PNG, JPG, BMP, TGA, PPM). Alpha is kept where the format has it and `keep_alpha` asks for it.
void write_8bit(const std::filesystem::path& path, Format format, const ImageRGBA8& image, bool keep_alpha,
                int jpeg_quality) {
  const int channels = keep_alpha && (format == Format::png || format == Format::tga) ? 4 : 3;
  const int w = image.width(), h = image.height();
  std::vector<unsigned char> bytes(image.pixels().size() * size_t(channels));
  unsigned char* byte = bytes.data();
  for (const glm::u8vec4& p : image.pixels())
    for (int c = 0; c < channels; ++c) *byte++ = p[c];
  AtomicFile file(path);
  std::ostream& out = file.stream();
  int ok = 1;
  switch (format) {
    case Format::png: {
      const std::string png = detail::encode_png(bytes.data(), w, h, channels);
      out.write(png.data(), std::streamsize(png.size()));
      break;
    }
    case Format::jpg:
      ok = stbi_write_jpg_to_func(stb_sink, &out, w, h, channels, bytes.data(), jpeg_quality);
      break;
    case Format::bmp:
      ok = stbi_write_bmp_to_func(stb_sink, &out, w, h, channels, bytes.data());
      break;
    case Format::tga:
      ok = stbi_write_tga_to_func(stb_sink, &out, w, h, channels, bytes.data());
      break;
    case Format::ppm:
      out << "P6\n" << w << ' ' << h << "\n255\n";
      out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
      break;
    case Format::hdr:
    case Format::pfm:
      throw InternalError("write_8bit called for a float format");
  }
  if (!ok) throw IoError(fmt::format("cannot write '{}': the image encoder failed", name_of(path)));
  file.commit();
}

// Float formats (HDR, PFM) from linear RGB.
void write_float_rgb(const std::filesystem::path& path, Format format, const ImageRGB& image) {
  std::vector<float> values;
  values.reserve(image.pixels().size() * 3);
  for (const glm::vec3& p : image.pixels()) values.insert(values.end(), {p.x, p.y, p.z});
  check_finite(path, values, image.width(), 3);
  AtomicFile file(path);
  if (format == Format::hdr) {
    if (!stbi_write_hdr_to_func(stb_sink, &file.stream(), image.width(), image.height(), 3, values.data()))
      throw IoError(fmt::format("cannot write '{}': the HDR encoder failed", name_of(path)));
  } else {
    write_pfm_stream(file.stream(), image.width(), image.height(), 3, values);
  }
  file.commit();
}

bool is_float_format(Format format) { return format == Format::hdr || format == Format::pfm; }

uint8_t to_byte(float v) {
  if (!(v > 0.f)) return 0;  // also NaN
  if (v >= 1.f) return 255;
  return uint8_t(std::lround(v * 255.f));
}

glm::u8vec4 encode_pixel(const glm::vec4& p, bool srgb) {
  const glm::vec3 rgb = srgb ? srgb_encode(glm::vec3(p)) : glm::vec3(p);
  return {to_byte(rgb.x), to_byte(rgb.y), to_byte(rgb.z), to_byte(p.w)};
}

}  // namespace

ImageRGBA read_image(const std::filesystem::path& path) {
  format_of(path, false);  // an unknown extension fails before the file is read
  return decode_image(read_file(path), path);
}

ImageRGBA decode_image(std::string_view data, const std::filesystem::path& path) {
  return std::get<ImageRGBA>(decode(data, path, false));
}

FileImage read_image_native(const std::filesystem::path& path) {
  format_of(path, false);  // an unknown extension fails before the file is read
  return decode_image_native(read_file(path), path);
}

FileImage decode_image_native(std::string_view data, const std::filesystem::path& path) {
  return decode(data, path, true);
}

void write_image(const std::filesystem::path& path, const ImageRGB& image, const WriteOptions& options) {
  const Format format = format_of(path, true);
  check_writable(path, image.width(), image.height(), options);
  if (is_float_format(format))
    write_float_rgb(path, format, image);
  else
    write_8bit(path, format, to_rgba8(image, options.srgb), false, options.jpeg_quality);
}

void write_image(const std::filesystem::path& path, const ImageRGBA& image, const WriteOptions& options) {
  const Format format = format_of(path, true);
  check_writable(path, image.width(), image.height(), options);
  if (is_float_format(format))
    write_float_rgb(path, format, to_rgb(image));
  else
    write_8bit(path, format, to_rgba8(image, options.srgb), true, options.jpeg_quality);
}

void write_image(const std::filesystem::path& path, const ImageRGBA8& image, const WriteOptions& options) {
  const Format format = format_of(path, true);
  check_writable(path, image.width(), image.height(), options);
  if (is_float_format(format))
    write_float_rgb(path, format, to_rgb(to_float(image, options.srgb)));
  else
    write_8bit(path, format, image, true, options.jpeg_quality);
}

void write_pfm(const std::filesystem::path& path, const DepthImage& image) {
  if (format_of(path, true) != Format::pfm)
    throw InvalidInput(fmt::format("'{}': write_pfm needs a .pfm file name", name_of(path)));
  check_writable(path, image.width(), image.height(), {});
  const std::vector<float> values(image.pixels().begin(), image.pixels().end());
  check_finite(path, values, image.width(), 1);
  write_file_atomic(path, [&](std::ostream& out) { write_pfm_stream(out, image.width(), image.height(), 1, values); });
}

DepthImage read_pfm_gray(const std::filesystem::path& path) {
  const Decoded d = read_pfm_data(read_file(path), name_of(path));
  DepthImage image(d.width, d.height);
  auto pixels = image.pixels();
  for (size_t i = 0; i < pixels.size(); ++i) {
    const float* v = &d.values[i * size_t(d.channels)];
    pixels[i] = d.channels == 1 ? v[0] : (v[0] + v[1] + v[2]) / 3.f;
  }
  return image;
}

ImageRGBA8 to_rgba8(const ImageRGB& image, bool srgb) {
  ImageRGBA8 out(image.width(), image.height());
  std::transform(image.pixels().begin(), image.pixels().end(), out.pixels().begin(),
                 [srgb](const glm::vec3& p) { return encode_pixel(glm::vec4(p, 1.f), srgb); });
  return out;
}

ImageRGBA8 to_rgba8(const ImageRGBA& image, bool srgb) {
  ImageRGBA8 out(image.width(), image.height());
  std::transform(image.pixels().begin(), image.pixels().end(), out.pixels().begin(),
                 [srgb](const glm::vec4& p) { return encode_pixel(p, srgb); });
  return out;
}

ImageRGBA to_float(const ImageRGBA8& image, bool srgb) {
  ImageRGBA out(image.width(), image.height());
  std::transform(image.pixels().begin(), image.pixels().end(), out.pixels().begin(), [srgb](const glm::u8vec4& p) {
    const glm::vec4 v = glm::vec4(p) / 255.f;
    return srgb ? glm::vec4(srgb_decode(glm::vec3(v)), v.w) : v;
  });
  return out;
}

ImageRGB to_rgb(const ImageRGBA& image) {
  ImageRGB out(image.width(), image.height());
  std::transform(image.pixels().begin(), image.pixels().end(), out.pixels().begin(),
                 [](const glm::vec4& p) { return glm::vec3(p); });
  return out;
}

ImageRGBA to_rgba(const ImageRGB& image) {
  ImageRGBA out(image.width(), image.height());
  std::transform(image.pixels().begin(), image.pixels().end(), out.pixels().begin(),
                 [](const glm::vec3& p) { return glm::vec4(p, 1.f); });
  return out;
}

}  // namespace tessera
