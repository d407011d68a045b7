// libFuzzer target for the parsers behind command-line values: the first byte picks one, the rest is the text.
// - core parse.hpp: parse_double (a finite result), parse_int, parse_doubles (3 or any count, all finite; `--origin`,
//   `--values`), parse_size (`--size`: both sides in 1..65536, at most 2^31 pixels), split and trim (split's parts
//   joined give the text back; trim leaves no outer white space), printable (no control byte, DEL or C1 control, valid
//   UTF-8 without overlong forms or surrogates, at most 4 bytes per kept character plus the "... (N bytes)" note);
// - parse_memory_size (`--max-memory`, memory_budget.hpp): at least 1 byte, then checked against the budget;
// - the two halves of the CLI's color values (apps/tessera parse_color is r,g,b through parse_doubles, else
//   parse_svg_color): components in [0, 1];
// - color models and hue units by name (`color convert --from/--to/--hue`), and convert() on `FROM TO v,v,v`.
// tessera::Error is the expected outcome for bad text, and its message must be printable in the same sense (input is
// quoted through printable(), so escape sequences never reach a terminal) and at most 1024 bytes. Anything else is a
// bug: a crash, another exception, a sanitizer report, or a broken invariant above (__builtin_trap).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "tessera/color/model.hpp"
#include "tessera/core/error.hpp"
#include "tessera/core/memory_budget.hpp"
#include "tessera/core/parse.hpp"
#include "tessera/svg/svg.hpp"

namespace {

void check(bool ok) {
  if (!ok) __builtin_trap();
}

// True when `text` is valid UTF-8 (RFC 3629: no overlong forms, surrogates or code points past U+10FFFF) holding no
// C0 control, DEL or C1 control: what a terminal shows as text.
bool is_printable(std::string_view text) {
  for (size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c < 0x80) {
      if (c < 0x20 || c == 0x7f) return false;
      ++i;
      continue;
    }
    const size_t len = c >= 0xc2 && c <= 0xdf ? 2 : c >= 0xe0 && c <= 0xef ? 3 : c >= 0xf0 && c <= 0xf4 ? 4 : 0;
    if (len == 0 || i + len > text.size()) return false;
    uint32_t code = c & (0xff >> (len + 1));
    for (size_t k = 1; k < len; ++k) {
      const auto b = static_cast<unsigned char>(text[i + k]);
      if ((b & 0xc0) != 0x80) return false;
      code = code << 6 | (b & 0x3f);
    }
    const uint32_t least[] = {0, 0, 0x80, 0x800, 0x10000};
    if (code < least[len] || (code >= 0xd800 && code <= 0xdfff) || code > 0x10ffff) return false;
    if (code >= 0x80 && code <= 0x9f) return false;  // C1 controls
    i += len;
  }
  return true;
}

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }

void check_color(const tessera::Vec4f& c) {
  for (int k = 0; k < 4; ++k) check(c[k] >= 0 && c[k] <= 1);  // also false for NaN
}

void run(uint8_t mode, std::string_view text) {
  using namespace tessera;
  switch (mode % 10) {
    case 0:
      check(std::isfinite(parse_double(text, "fuzz")));
      break;
    case 1: {
      const long long v = parse_int(text, "fuzz");
      check(parse_int(std::to_string(v), "fuzz") == v);
      break;
    }
    case 2: {
      const size_t count = mode / 16 % 2 ? 3 : 0;
      const std::vector<double> v = parse_doubles(text, count, "fuzz");
      check(!v.empty() && (count == 0 || v.size() == count));
      for (double x : v) check(std::isfinite(x));
      break;
    }
    case 3: {
      const Size2 s = parse_size(text, "fuzz");
      check(s.width >= 1 && s.width <= 65536 && s.height >= 1 && s.height <= 65536);
      check((long long)s.width * s.height <= (1LL << 31));
      break;
    }
    case 4: {
      const char delimiter = text.empty() ? ',' : text[0];
      const auto parts = split(text, delimiter);
      std::string joined;
      for (size_t i = 0; i < parts.size(); ++i) {
        if (i > 0) joined += delimiter;
        joined += parts[i];
      }
      check(joined == text);
      const std::string_view t = trim(text);
      check(t.empty() || (!is_space(t.front()) && !is_space(t.back())));
      check(t.empty() || text.find(t) != std::string_view::npos);
      break;
    }
    case 5: {
      const size_t max_chars = mode / 16;  // 0..15, and the default below
      for (const std::string& p : {printable(text, max_chars), printable(text)}) {
        check(is_printable(p));
        check(p.size() <= 4 * 60 + 32);
      }
      break;
    }
    case 6: {
      const uint64_t bytes = parse_memory_size(text, "fuzz");
      check(bytes >= 1);
      check(!format_bytes(bytes).empty());
      MemoryBudget::check(bytes, "fuzz");
      break;
    }
    case 7:
      check_color(parse_svg_color(text));
      break;
    case 8:
      if (mode / 16 % 2)
        parse_hue_unit(text);
      else
        parse_color_model(text);
      break;
    case 9: {
      const auto words = split(text, ' ');
      if (words.size() != 3) return;
      const ColorModel from = parse_color_model(words[0]), to = parse_color_model(words[1]);
      const std::vector<double> in = parse_doubles(words[2], size_t(component_count(from)), "fuzz");
      const std::vector<double> out = convert(from, to, in);
      check(out.size() == size_t(component_count(to)));
      break;
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  tessera::MemoryBudget::set_limit(uint64_t(256) << 20);
  try {
    run(data[0], std::string_view(reinterpret_cast<const char*>(data) + 1, size - 1));
  } catch (const tessera::Error& e) {
    const std::string_view message = e.what();
    check(is_printable(message) && message.size() <= 1024);
  }
  return 0;
}
