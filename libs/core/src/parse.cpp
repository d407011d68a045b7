#include "tessera/core/parse.hpp"

#include <charconv>
#include <cmath>

#include "tessera/core/error.hpp"

namespace tessera {

std::string_view trim(std::string_view text) {
  const auto is_space = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; };
  while (!text.empty() && is_space(text.front())) text.remove_prefix(1);
  while (!text.empty() && is_space(text.back())) text.remove_suffix(1);
  return text;
}

std::vector<std::string_view> split(std::string_view text, char delimiter) {
  std::vector<std::string_view> parts;
  size_t start = 0;
  for (;;) {
    const size_t end = text.find(delimiter, start);
    parts.push_back(text.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start));
    if (end == std::string_view::npos) break;
    start = end + 1;
  }
  return parts;
}

std::string printable(std::string_view text, size_t max_chars) {
  std::string out;
  size_t chars = 0, i = 0;
  for (; i < text.size() && chars < max_chars; ++chars) {
    const auto c = static_cast<unsigned char>(text[i]);
    // Length of a well-formed UTF-8 sequence starting here (0: not one); C1 controls (U+0080..U+009F) are escaped.
    size_t len = c >= 0xc2 && c <= 0xdf ? 2 : c >= 0xe0 && c <= 0xef ? 3 : c >= 0xf0 && c <= 0xf4 ? 4 : 0;
    if (len > 1 && i + len <= text.size()) {
      for (size_t k = 1; k < len; ++k)
        if ((static_cast<unsigned char>(text[i + k]) & 0xc0) != 0x80) len = 0;
      // C1 controls, and the forms RFC 3629 forbids (overlong, surrogates, past U+10FFFF): a lenient terminal could
      // decode the overlong E0 80 9B as ESC.
      const auto c1 = static_cast<unsigned char>(text[i + 1]);
      if ((c == 0xc2 && c1 < 0xa0) || (c == 0xe0 && c1 < 0xa0) || (c == 0xed && c1 >= 0xa0) ||
          (c == 0xf0 && c1 < 0x90) || (c == 0xf4 && c1 >= 0x90))
        len = 0;
    } else {
      len = 0;
    }
    if (len > 1) {
      out.append(text.substr(i, len));
      i += len;
      continue;
    }
    switch (c) {
      case '\n':
        out += "\\n";
        break;
      case '\r':
        out += "\\r";
        break;
      case '\t':
        out += "\\t";
        break;
      case '\\':
        out += "\\\\";
        break;
      default:
        if (c < 0x20 || c >= 0x7f)
          out += fmt::format("\\x{:02x}", c);
        else
          out += char(c);
    }
    ++i;
  }
  if (i < text.size()) out += fmt::format("... ({} bytes)", text.size());
  return out;
}

double parse_double(std::string_view text, std::string_view what) {
  const std::string_view t = trim(text);
  double value = 0;
  const char* first = t.data();
  if (!t.empty() && *first == '+') ++first;
  const auto [end, ec] = std::from_chars(first, t.data() + t.size(), value);
  if (t.empty() || ec != std::errc() || end != t.data() + t.size() || !std::isfinite(value))
    throw InvalidInput(fmt::format("{}: expected a number, got '{}'", what, printable(text)));
  return value;
}

long long parse_int(std::string_view text, std::string_view what) {
  const std::string_view t = trim(text);
  long long value = 0;
  const char* first = t.data();
  if (!t.empty() && *first == '+') ++first;
  const auto [end, ec] = std::from_chars(first, t.data() + t.size(), value);
  if (t.empty() || ec != std::errc() || end != t.data() + t.size())
    throw InvalidInput(fmt::format("{}: expected an integer, got '{}'", what, printable(text)));
  return value;
}

std::vector<double> parse_doubles(std::string_view text, size_t count, std::string_view what) {
  const auto parts = split(text, ',');
  if (count != 0 && parts.size() != count)
    throw InvalidInput(fmt::format("{}: expected {} comma-separated numbers, got '{}'", what, count, printable(text)));
  std::vector<double> values;
  values.reserve(parts.size());
  for (auto p : parts) values.push_back(parse_double(p, what));
  return values;
}

Size2 parse_size(std::string_view text, std::string_view what) {
  const size_t x = text.find_first_of("xX");
  if (x == std::string_view::npos)
    throw InvalidInput(fmt::format("{}: expected WIDTHxHEIGHT, got '{}'", what, printable(text)));
  const long long w = parse_int(text.substr(0, x), what);
  const long long h = parse_int(text.substr(x + 1), what);
  if (w <= 0 || h <= 0 || w > 65536 || h > 65536)
    throw InvalidInput(fmt::format("{}: width and height must be in 1..65536, got '{}'", what, printable(text)));
  // The most pixels one Image holds (image.hpp); larger sizes pass the per-side range but could never be allocated.
  constexpr long long kMaxPixels = 1LL << 31;
  if (w * h > kMaxPixels)
    throw InvalidInput(fmt::format("{}: {}x{} is {} pixels, more than the {} (2^31) an image can hold", what, w, h,
                                   w * h, kMaxPixels));
  return {int(w), int(h)};
}

}  // namespace tessera
