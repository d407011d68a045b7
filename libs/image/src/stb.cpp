// stb_image (PNG, BMP, TGA and Radiance HDR; JPEG goes to libjpeg-turbo, jpeg_decode.cpp) and stb_image_write,
// compiled here from Debian's libstb-dev headers rather than linked from its libstb, so that every buffer stb allocates
// starts zeroed and stb decodes no format Tessera does not name (GIF, PSD, PIC and PNM stay out). stb_image reads
// memory it never wrote on some corrupt files (a JPEG without the quantization tables its frame names decodes from an
// uninitialized struct, found by fuzz_image_formats): with plain malloc such a file decodes differently from one run to
// the next. Zeroed allocations make every decode of a file the same, and compiling stb with the project lets the
// sanitizers and the fuzzers see inside it.
#include <cstdint>
#include <cstdlib>
#include <cstring>

#include "tessera/core/memory_budget.hpp"

namespace {

// No single stb buffer may exceed the memory budget: stb sizes some from what a file declares before reading it (the
// output of a PNG's deflate stream grows as far as the stream says), and fails with "outofmem" instead. Small buffers
// skip the check, which reads /proc when no --max-memory was given.
bool within_budget(size_t size) { return size <= (size_t(64) << 20) || size <= tessera::MemoryBudget::bytes(); }

void* stb_zeroed_malloc(size_t size) { return within_budget(size) ? std::calloc(1, size) : nullptr; }

// Grows like realloc and zeroes the bytes past `old_size`.
void* stb_zeroed_realloc(void* p, size_t old_size, size_t new_size) {
  if (!within_budget(new_size)) return nullptr;
  auto* grown = static_cast<unsigned char*>(std::realloc(p, new_size));
  if (grown && new_size > old_size) std::memset(grown + old_size, 0, new_size - old_size);
  return grown;
}

}  // namespace

#define STBI_MALLOC(size) stb_zeroed_malloc(size)
#define STBI_REALLOC_SIZED(p, old_size, new_size) stb_zeroed_realloc(p, old_size, new_size)
#define STBI_FREE(p) std::free(p)
#define STBI_NO_STDIO
#define STBI_ONLY_PNG
#define STBI_ONLY_BMP
#define STBI_ONLY_TGA
#define STBI_ONLY_HDR
#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>

// Not STBI_WRITE_NO_STDIO: this stb version compiles its whole HDR writer, stbi_write_hdr_to_func too, only with stdio.
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>
