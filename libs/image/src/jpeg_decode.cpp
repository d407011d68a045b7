#include "jpeg_decode.hpp"

// jpeglib.h needs FILE and size_t declared first.
#include <cstddef>
#include <cstdio>
// clang-format off
#include <jpeglib.h>
#include <jerror.h>
// clang-format on

#include <csetjmp>
#include <vector>

#include "pixel_budget.hpp"
#include "tessera/core/error.hpp"

namespace tessera::detail {
namespace {

// libjpeg reports an error by calling error_exit, which must not return: it formats the message and longjmps back to
// the setjmp in jpeg_step. Only libjpeg's frames and jpeg_step's step lambdas (no destructors) lie in between.
struct ErrorManager {
  jpeg_error_mgr base;
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX];
};

[[noreturn]] void on_error(j_common_ptr info) {
  auto* manager = reinterpret_cast<ErrorManager*>(info->err);
  info->err->format_message(info, manager->message);
  std::longjmp(manager->jump, 1);
}

// Truncated or damaged entropy-coded data is only a warning to libjpeg, which then decodes the rest of the image as
// gray; Tessera refuses such a file rather than return pixels the file does not hold. The other warnings (extraneous
// bytes before a marker, an unknown JFIF revision or Adobe transform, a bad ICC marker, an odd progression) leave the
// pixels as the file gives them and are ignored; trace messages (level >= 0) too.
void on_message(j_common_ptr info, int level) {
  if (level >= 0) return;
  switch (info->err->msg_code) {
    case JWRN_JPEG_EOF:
    case JWRN_HIT_MARKER:
    case JWRN_HUFF_BAD_CODE:
    case JWRN_ARITH_BAD_CODE:
    case JWRN_MUST_RESYNC:
      on_error(info);
    default:
      break;
  }
}

// A decompressor whose error handler throws through jpeg_step; destroyed whatever state it was left in.
struct Decompressor {
  jpeg_decompress_struct info{};
  ErrorManager errors{};

  Decompressor() {
    info.err = jpeg_std_error(&errors.base);
    errors.base.error_exit = on_error;
    errors.base.emit_message = on_message;
  }
  Decompressor(const Decompressor&) = delete;
  Decompressor& operator=(const Decompressor&) = delete;
  ~Decompressor() { jpeg_destroy_decompress(&info); }

  // Runs `step` (libjpeg calls on plain data only: a longjmp skips no destructor) and turns a libjpeg error into
  // InvalidInput naming the file and the byte libjpeg had read to.
  template <class Step>
  void jpeg_step(std::string_view data, const std::string& name, const Step& step) {
    if (setjmp(errors.jump)) {
      const size_t offset = info.src ? data.size() - info.src->bytes_in_buffer : 0;
      throw InvalidInput(fmt::format("'{}': cannot decode JPEG at byte {}: {}", name, offset, errors.message));
    }
    step();
  }
};

// x * y / 255 rounded, as Adobe's inverted CMYK is turned into RGB (each channel times black).
uint8_t times_black(unsigned x, unsigned k) {
  const unsigned t = x * k + 128;
  return uint8_t((t + (t >> 8)) >> 8);
}

}  // namespace

bool is_jpeg(std::string_view data) {
  return data.size() >= 3 && data[0] == '\xFF' && data[1] == '\xD8' && data[2] == '\xFF';
}

FileImage decode_jpeg(std::string_view data, const std::string& name, bool keep_8bit) {
  Decompressor d;
  d.jpeg_step(data, name, [&] {
    jpeg_create_decompress(&d.info);
    jpeg_mem_src(&d.info, reinterpret_cast<const unsigned char*>(data.data()), static_cast<unsigned long>(data.size()));
    jpeg_read_header(&d.info, TRUE);
  });
  const bool cmyk = d.info.jpeg_color_space == JCS_CMYK || d.info.jpeg_color_space == JCS_YCCK;
  d.info.out_color_space = cmyk ? JCS_CMYK : JCS_EXT_RGBA;
  // The image, its float copy, and the whole-image coefficient buffers libjpeg keeps for a progressive or multi-scan
  // file (64 two-byte coefficients per 8x8 block of each component).
  const int width = int(d.info.image_width), height = int(d.info.image_height);
  const uint64_t coefficients = jpeg_has_multiple_scans(&d.info) ? 2 * uint64_t(d.info.num_components) : 0;
  check_pixel_count(name, width, height,
                    sizeof(ImageRGBA8::Pixel) + (keep_8bit ? 0 : sizeof(ImageRGBA::Pixel)) + coefficients);

  ImageRGBA8 image(width, height);
  std::vector<JSAMPLE> cmyk_row(cmyk ? size_t(width) * 4 : 0);
  d.jpeg_step(data, name, [&] {
    jpeg_start_decompress(&d.info);
    while (d.info.output_scanline < d.info.output_height) {
      auto* rgba = reinterpret_cast<JSAMPLE*>(image.row(int(d.info.output_scanline)));
      JSAMPROW row = cmyk ? cmyk_row.data() : rgba;
      jpeg_read_scanlines(&d.info, &row, 1);
      for (size_t x = 0; cmyk && x < size_t(width); ++x) {
        const JSAMPLE* c = &cmyk_row[4 * x];
        rgba[4 * x] = times_black(c[0], c[3]);
        rgba[4 * x + 1] = times_black(c[1], c[3]);
        rgba[4 * x + 2] = times_black(c[2], c[3]);
        rgba[4 * x + 3] = 255;
      }
    }
    // Not jpeg_finish_decompress: the pixels are all read, and what follows them (EOI, trailing bytes) cannot change
    // them.
  });
  if (keep_8bit) return image;
  return to_float(image);
}

}  // namespace tessera::detail
