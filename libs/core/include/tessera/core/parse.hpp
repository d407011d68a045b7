#pragma once
// Strict text-to-number parsing for command-line values and text file formats.
// Every function rejects trailing garbage, NaN and infinity, and throws InvalidInput naming `what`.
#include <string>
#include <string_view>
#include <vector>

namespace tessera {

/// Input text made safe to quote in a message: control bytes, DEL and bytes that are not valid UTF-8 become escapes
/// (\n, \t, \x1b, ...), so an error can never send escape sequences to a terminal, and text longer than
/// `max_chars` characters is cut there with "... (N bytes)" appended, so a 10 MB line cannot flood it.
std::string printable(std::string_view text, size_t max_chars = 60);

/// Parses a finite double ("1.5", "-2e3"). Throws InvalidInput "<what>: expected a number, got '<text>'" (the text
/// through printable(), as in every message below).
double parse_double(std::string_view text, std::string_view what);

/// Parses a base-10 integer that fits in long long.
long long parse_int(std::string_view text, std::string_view what);

/// Parses `count` comma-separated finite doubles ("1,2,3"); count 0 accepts any number of at least one.
std::vector<double> parse_doubles(std::string_view text, size_t count, std::string_view what);

/// Parses "WxH" with both positive, at most 65536 each and at most 2^31 pixels in all (what an Image holds); the
/// message of a rejected size states the limit it breaks.
struct Size2 {
  int width, height;
};
Size2 parse_size(std::string_view text, std::string_view what);

/// Splits on a delimiter, keeping empty fields.
std::vector<std::string_view> split(std::string_view text, char delimiter);

/// Removes leading and trailing ASCII white space.
std::string_view trim(std::string_view text);

}  // namespace tessera
