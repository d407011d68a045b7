// The XML reader of the svg module (xml.hpp): XML 1.0 well-formedness for what an SVG file holds.
#include "xml.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <utility>

#include "tessera/core/error.hpp"
#include "tessera/core/parse.hpp"

namespace tessera::xml {
namespace {

bool is_name_start(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_' || c == ':' ||
         static_cast<unsigned char>(c) >= 0x80;
}
bool is_name_char(char c) { return is_name_start(c) || (c >= '0' && c <= '9') || c == '-' || c == '.'; }

// Appends the UTF-8 encoding of a code point.
void append_utf8(std::string& out, uint32_t cp) {
  if (cp < 0x80) {
    out.push_back(char(cp));
  } else if (cp < 0x800) {
    out.push_back(char(0xc0 | (cp >> 6)));
    out.push_back(char(0x80 | (cp & 0x3f)));
  } else if (cp < 0x10000) {
    out.push_back(char(0xe0 | (cp >> 12)));
    out.push_back(char(0x80 | ((cp >> 6) & 0x3f)));
    out.push_back(char(0x80 | (cp & 0x3f)));
  } else {
    out.push_back(char(0xf0 | (cp >> 18)));
    out.push_back(char(0x80 | ((cp >> 12) & 0x3f)));
    out.push_back(char(0x80 | ((cp >> 6) & 0x3f)));
    out.push_back(char(0x80 | (cp & 0x3f)));
  }
}

// XML 1.0 Char production.
bool is_xml_char(uint32_t cp) {
  return cp == 0x9 || cp == 0xa || cp == 0xd || (cp >= 0x20 && cp <= 0xd7ff) || (cp >= 0xe000 && cp <= 0xfffd) ||
         (cp >= 0x10000 && cp <= 0x10ffff);
}

}  // namespace

SourceMap::SourceMap(std::string_view text, std::string name) : name_(std::move(name)) {
  line_starts_.push_back(0);
  for (size_t i = 0; i < text.size(); ++i)
    if (text[i] == '\n') line_starts_.push_back(i + 1);
}

long SourceMap::line(size_t offset) const {
  return long(std::upper_bound(line_starts_.begin(), line_starts_.end(), offset) - line_starts_.begin());
}

std::string SourceMap::where(size_t offset) const {
  const long l = line(offset);
  return fmt::format("{}:{}:{}", name_, l, offset - line_starts_[size_t(l - 1)] + 1);
}

void SourceMap::fail(size_t offset, const std::string& what) const { fail_escaped(offset, printable(what, 400)); }

void SourceMap::fail_escaped(size_t offset, const std::string& what) const {
  throw InvalidInput(located(where(offset), what));
}

Reader::Reader(std::string_view text, const SourceMap& map, std::string_view root)
    : text_(text), map_(map), root_(root) {
  if (text_.substr(0, 3) == "\xef\xbb\xbf") pos_ = 3;  // UTF-8 byte order mark
}

Event Reader::next() {
  if (pending_end_) {
    pending_end_ = false;
    return close_top();
  }
  for (;;) {
    if (pos_ >= text_.size()) {
      if (!open_.empty())
        map_.fail(pos_, fmt::format("unexpected end of file: expected </{}> to close <{}> from line {}",
                                    open_.back().name, open_.back().name, map_.line(open_.back().offset)));
      if (!root_seen_) map_.fail(pos_, fmt::format("no root element: expected <{}>", root_));
      return {Event::Kind::eof, {}, pos_, {}};
    }
    if (text_[pos_] != '<') {
      text();
    } else if (starts_with("<?")) {
      skip_past("?>", "unterminated processing instruction (expected '?>')");
    } else if (starts_with("<!--")) {
      skip_past("-->", "unterminated comment (expected '-->')");
    } else if (starts_with("<![CDATA[")) {
      if (open_.empty()) map_.fail(pos_, "CDATA section outside the root element");
      skip_past("]]>", "unterminated CDATA section (expected ']]>')");
    } else if (starts_with("<!DOCTYPE")) {
      if (root_seen_) map_.fail(pos_, "DOCTYPE after the root element");
      skip_doctype();
    } else if (starts_with("<!")) {
      map_.fail(pos_, "expected a comment '<!--', CDATA '<![CDATA[' or '<!DOCTYPE' after '<!'");
    } else if (starts_with("</")) {
      return end_tag();
    } else {
      return start_tag();
    }
  }
}

bool Reader::starts_with(std::string_view s) const { return text_.substr(pos_, s.size()) == s; }

bool Reader::skip_space() {
  const size_t start = pos_;
  while (pos_ < text_.size() && is_space(text_[pos_])) ++pos_;
  return pos_ > start;
}

void Reader::skip_past(std::string_view marker, const char* unterminated) {
  const size_t end = text_.find(marker, pos_);
  if (end == std::string_view::npos) map_.fail(pos_, unterminated);
  pos_ = end + marker.size();
}

// <!DOCTYPE ...> with an optional internal subset [...] and quoted literals.
void Reader::skip_doctype() {
  const size_t start = pos_;
  int depth = 0;
  char quote = 0;
  for (pos_ += 2; pos_ < text_.size(); ++pos_) {
    const char c = text_[pos_];
    if (quote) {
      if (c == quote) quote = 0;
    } else if (c == '"' || c == '\'') {
      quote = c;
    } else if (c == '[') {
      ++depth;
    } else if (c == ']') {
      --depth;
    } else if (c == '>' && depth <= 0) {
      ++pos_;
      return;
    }
  }
  map_.fail(start, "unterminated DOCTYPE (expected '>')");
}

std::string Reader::read_name(const char* what) {
  const size_t start = pos_;
  if (pos_ >= text_.size() || !is_name_start(text_[pos_]))
    map_.fail(pos_, pos_ >= text_.size() ? fmt::format("expected {}, got the end of the file", what)
                                         : fmt::format("expected {}, got '{}'", what, text_[pos_]));
  while (pos_ < text_.size() && is_name_char(text_[pos_])) ++pos_;
  return std::string(text_.substr(start, pos_ - start));
}

// &amp; &lt; &gt; &quot; &apos; &#N; &#xH; at pos_ (which holds '&'): appends the character and moves past ';'.
void Reader::entity(std::string& out) {
  const size_t start = pos_;
  const size_t semi = text_.find(';', pos_);
  if (semi == std::string_view::npos || semi - pos_ > 12)
    map_.fail(start, "expected an entity such as '&amp;' (an '&' must be written '&amp;')");
  const std::string_view name = text_.substr(pos_ + 1, semi - pos_ - 1);
  pos_ = semi + 1;
  static constexpr std::pair<std::string_view, char> kNamed[] = {
      {"amp", '&'}, {"lt", '<'}, {"gt", '>'}, {"quot", '"'}, {"apos", '\''}};
  for (const auto& [n, c] : kNamed)
    if (name == n) return out.push_back(c);
  if (name.size() >= 2 && name[0] == '#') {
    const bool hex = name[1] == 'x';
    const std::string_view digits = name.substr(hex ? 2 : 1);
    uint32_t cp = 0;
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), cp, hex ? 16 : 10);
    if (!digits.empty() && ec == std::errc() && end == digits.data() + digits.size() && is_xml_char(cp))
      return append_utf8(out, cp);
    map_.fail(start, fmt::format("invalid character reference '&{};'", name));
  }
  map_.fail(start, fmt::format("unknown entity '&{};' (XML knows &amp; &lt; &gt; &quot; &apos; and &#N;)", name));
}

// Character data: ignored, but entities must be valid and only white space may stand outside the root.
void Reader::text() {
  std::string scratch;
  while (pos_ < text_.size() && text_[pos_] != '<') {
    if (text_[pos_] == '&') {
      if (open_.empty()) map_.fail(pos_, "text outside the root element");
      entity(scratch);
      continue;
    }
    if (open_.empty() && !is_space(text_[pos_]))
      map_.fail(pos_, root_closed_ ? "content after the end of the root element" : "text before the root element");
    ++pos_;
  }
}

Event Reader::start_tag() {
  const size_t start = pos_++;
  if (root_closed_) map_.fail(start, "content after the end of the root element");
  Event event{Event::Kind::start, read_name("an element name after '<'"), start, {}};
  for (;;) {
    const bool space = skip_space();
    if (pos_ >= text_.size())
      map_.fail(pos_, fmt::format("unexpected end of file inside the <{}> tag (expected '>' or '/>')", event.name));
    if (text_[pos_] == '>') {
      ++pos_;
      break;
    }
    if (starts_with("/>")) {
      pos_ += 2;
      pending_end_ = true;
      break;
    }
    if (!space)
      map_.fail(pos_,
                fmt::format("expected white space, '>' or '/>' in the <{}> tag, got '{}'", event.name, text_[pos_]));
    event.attributes.push_back(attribute(event));
  }
  root_seen_ = true;
  open_.push_back({event.name, start});
  return event;
}

Attribute Reader::attribute(const Event& event) {
  Attribute a{{}, {}, pos_, 0, true};
  a.name = read_name("an attribute name");
  skip_space();
  if (pos_ >= text_.size() || text_[pos_] != '=')
    map_.fail(pos_, fmt::format("expected '=' after attribute '{}'", a.name));
  ++pos_;
  skip_space();
  const char quote = pos_ < text_.size() ? text_[pos_] : '\0';
  if (quote != '"' && quote != '\'') map_.fail(pos_, fmt::format("expected a quoted value for attribute '{}'", a.name));
  a.value_offset = ++pos_;
  for (;;) {
    if (pos_ >= text_.size())
      map_.fail(a.value_offset - 1, fmt::format("unterminated value of attribute '{}' (expected {})", a.name, quote));
    const char c = text_[pos_];
    if (c == quote) break;
    if (c == '<') map_.fail(pos_, fmt::format("'<' in the value of attribute '{}' (write &lt;)", a.name));
    if (c == '&') {
      entity(a.value);
      a.verbatim = false;
      continue;
    }
    a.value.push_back(is_space(c) ? ' ' : c);
    ++pos_;
  }
  ++pos_;
  for (const Attribute& other : event.attributes)
    if (other.name == a.name) map_.fail(a.name_offset, fmt::format("duplicate attribute '{}'", a.name));
  return a;
}

Event Reader::end_tag() {
  const size_t start = pos_;
  pos_ += 2;
  const std::string name = read_name("an element name after '</'");
  skip_space();
  if (pos_ >= text_.size() || text_[pos_] != '>') map_.fail(pos_, fmt::format("expected '>' to end </{}>", name));
  ++pos_;
  if (open_.empty()) map_.fail(start, fmt::format("unexpected </{}>: no element is open", name));
  if (open_.back().name != name)
    map_.fail(start, fmt::format("expected </{}> to close <{}> from line {}, got </{}>", open_.back().name,
                                 open_.back().name, map_.line(open_.back().offset), name));
  Event event = close_top();
  event.offset = start;
  return event;
}

Event Reader::close_top() {
  Event event{Event::Kind::end, std::move(open_.back().name), open_.back().offset, {}};
  open_.pop_back();
  root_closed_ = open_.empty();
  return event;
}

}  // namespace tessera::xml
