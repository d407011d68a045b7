#include "tessera/curves/bpt.hpp"

#include <fmt/format.h>

#include <cstdint>

#include "tessera/core/atomic_file.hpp"
#include "tessera/core/error.hpp"
#include "tessera/core/parse.hpp"

namespace tessera {
namespace {

// Splits text into white-space-separated tokens, tracking the line of each.
class Tokenizer {
 public:
  Tokenizer(std::string_view text, const std::string& name) : text_(text), name_(name) {}

  /// The next token, or throws "name:LINE: expected <what>, got end of file" (LINE: that of the last token).
  std::string_view next(const std::string& what) {
    skip_space();
    if (pos_ == text_.size()) throw InvalidInput(located(where(), fmt::format("expected {}, got end of file", what)));
    token_line_ = line_;
    const size_t start = pos_;
    while (pos_ < text_.size() && !is_space(text_[pos_])) ++pos_;
    return text_.substr(start, pos_ - start);
  }
  /// Throws when anything but white space is left.
  void expect_end() {
    skip_space();
    if (pos_ != text_.size()) {
      token_line_ = line_;
      throw InvalidInput(located(where(), fmt::format("expected end of file after the last patch, got '{}'",
                                                      printable(text_.substr(pos_), 20))));
    }
  }
  /// "name:LINE" of the last token read.
  std::string where() const { return at_line(name_, token_line_); }
  size_t remaining() const { return text_.size() - pos_; }

 private:
  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }
  void skip_space() {
    while (pos_ < text_.size() && is_space(text_[pos_])) line_ += text_[pos_++] == '\n';
  }

  std::string_view text_;
  const std::string& name_;
  size_t pos_ = 0;
  long line_ = 1;        // line of the read position
  long token_line_ = 1;  // line of the last token
};

// The fewest bytes one patch can take: 2 + 48 tokens of at least one character, each after a separator.
constexpr size_t kMinPatchBytes = 2 * (2 + 48);

}  // namespace

std::vector<BezierPatch> parse_bpt(std::string_view text, const std::string& name) {
  Tokenizer tokens(text, name);
  const std::string_view count_text = tokens.next("the patch count");
  const long long count = parse_int(count_text, located(tokens.where(), "the patch count"));
  if (count < 0) throw InvalidInput(located(tokens.where(), fmt::format("expected a patch count >= 0, got {}", count)));
  if (size_t(count) > tokens.remaining() / kMinPatchBytes)
    throw InvalidInput(located(
        tokens.where(),
        fmt::format("patch count {} needs at least {} bytes ({} per patch), {} are left", count,
                    size_t(count) <= SIZE_MAX / kMinPatchBytes ? fmt::format("{}", size_t(count) * kMinPatchBytes)
                                                               : fmt::format("more than {}", SIZE_MAX),
                    kMinPatchBytes, tokens.remaining())));
  std::vector<BezierPatch> patches(static_cast<size_t>(count));
  for (size_t p = 0; p < patches.size(); ++p) {
    for (const char* axis : {"u", "v"}) {
      const std::string what = fmt::format("the {} degree of patch {}", axis, p + 1);
      const long long degree = parse_int(tokens.next(what), located(tokens.where(), what));
      if (degree != 3)
        throw InvalidInput(located(tokens.where(), fmt::format("expected {} to be 3 (bicubic), got {}", what, degree)));
    }
    for (size_t k = 0; k < 16; ++k)
      for (int c = 0; c < 3; ++c) {
        const std::string what = fmt::format("{} of control point {} of patch {}", "xyz"[c], k + 1, p + 1);
        patches[p].points[k][c] = parse_double(tokens.next(what), located(tokens.where(), what));
      }
  }
  tokens.expect_end();
  return patches;
}

std::vector<BezierPatch> read_bpt(const std::filesystem::path& path) {
  return parse_bpt(read_file(path), path.string());
}

std::string format_bpt(std::span<const BezierPatch> patches) {
  std::string out = fmt::format("{}\n", patches.size());
  for (const BezierPatch& patch : patches) {
    out += "3 3\n";
    for (const Vec3& p : patch.points) out += fmt::format("{} {} {}\n", p.x, p.y, p.z);
  }
  return out;
}

void write_bpt(const std::filesystem::path& path, std::span<const BezierPatch> patches) {
  write_file_atomic(path, format_bpt(patches));
}

}  // namespace tessera
