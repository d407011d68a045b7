#pragma once
// Private to the svg module: a small strict XML reader. It checks XML 1.0 well-formedness for what an SVG file holds
// (elements, attributes, the five predefined and numeric entities, comments, processing instructions, CDATA and a
// DOCTYPE that is skipped) and hands out start and end tags as events; character data is checked and dropped. It is
// private because nothing else in Tessera reads XML: a second user would move it down into its own module.
#include <string>
#include <string_view>
#include <vector>

namespace tessera::xml {

/// True for XML white space (space, tab, CR, LF).
constexpr bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }

/// Line and column (1-based, in bytes) of offsets in a source text, for messages.
class SourceMap {
 public:
  SourceMap(std::string_view text, std::string name);

  /// The 1-based line holding byte `offset`.
  long line(size_t offset) const;

  /// "name:line:column" of byte `offset`.
  std::string where(size_t offset) const;

  /// Throws InvalidInput "name:line:column: what", quoting `what` through printable() (it holds the document's own
  /// bytes, which must not reach a terminal as escape sequences).
  [[noreturn]] void fail(size_t offset, const std::string& what) const;
  /// Throws as fail, without escaping `what`: for messages whose pieces of input went through printable() already
  /// (escaping twice would double their backslashes).
  [[noreturn]] void fail_escaped(size_t offset, const std::string& what) const;

  const std::string& name() const { return name_; }

 private:
  std::string name_;
  std::vector<size_t> line_starts_;
};

/// One attribute of a start tag.
struct Attribute {
  std::string name;
  std::string value;    ///< entities decoded, white space characters normalized to spaces
  size_t name_offset;   ///< in the source
  size_t value_offset;  ///< of the value's first character in the source
  bool verbatim;        ///< no entity in the value: offsets inside it map one to one onto the source
};

/// A start tag (an empty-element tag gives a Start and then an End), an end tag, or the end of the document.
struct Event {
  enum class Kind { start, end, eof };
  Kind kind;
  std::string name;
  size_t offset;  ///< of the tag's '<' (for an empty element's End, that of its start tag)
  std::vector<Attribute> attributes;
};

/// Pulls start and end tags out of the text, checking well-formedness: one root element, matching end tags, quoted
/// unique attributes, known entities, nothing but white space, comments and processing instructions outside the root.
/// Every violation throws InvalidInput naming name:line:column (SourceMap::fail) and what was expected.
class Reader {
 public:
  /// Reads `text` (a UTF-8 byte order mark is skipped); `map` must be the map of the same text and outlive the
  /// reader. `root` names the root element the caller expects, for the message when the document has none.
  Reader(std::string_view text, const SourceMap& map, std::string_view root);

  /// The next tag; after the root's end tag, Eof (and Eof again on every later call).
  Event next();

 private:
  bool starts_with(std::string_view s) const;
  bool skip_space();
  void skip_past(std::string_view marker, const char* unterminated);
  void skip_doctype();
  std::string read_name(const char* what);
  void entity(std::string& out);
  void text();
  Event start_tag();
  Attribute attribute(const Event& event);
  Event end_tag();
  Event close_top();

  struct OpenElement {
    std::string name;
    size_t offset;
  };
  std::string_view text_;
  const SourceMap& map_;
  std::string root_;
  size_t pos_ = 0;
  std::vector<OpenElement> open_;
  bool root_seen_ = false, root_closed_ = false, pending_end_ = false;
};

}  // namespace tessera::xml
