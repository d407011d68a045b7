#pragma once
// Shared pieces of the mesh readers and writers: error helpers, a text cursor over a memory buffer (line counting,
// std::from_chars numbers) and little/big endian scalars.
#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "tessera/core/error.hpp"
#include "tessera/core/parse.hpp"
#include "tessera/core/progress.hpp"
#include "tessera/mesh/poly_mesh.hpp"

namespace tessera::mesh_io {

/// Throws InvalidInput "name:line: what".
[[noreturn]] inline void fail_at_line(const std::string& name, long line, const std::string& what) {
  throw InvalidInput(located(at_line(name, line), what));
}

/// Throws InvalidInput "name: byte offset N: what".
[[noreturn]] inline void fail_at_byte(const std::string& name, long long offset, const std::string& what) {
  throw InvalidInput(located(at_byte(name, offset), what));
}

/// Reports how far a reader has got through its data to a Progress (whose total is the data's size), in steps of
/// 1 MiB so that the check costs one comparison per line or row. Does nothing without a Progress.
class ByteProgress {
 public:
  ByteProgress(Progress* progress, std::string_view data)
      : progress_(progress), reported_(data.data()), next_(data.data() + kStep), end_(data.data() + data.size()) {}
  /// The reader has parsed everything before `position`.
  void at(const char* position) {
    if (progress_ != nullptr && position >= next_) report(position);
  }
  /// The reader is done: the rest of the data counts as parsed.
  void finish() {
    if (progress_ != nullptr) report(end_);
  }

 private:
  static constexpr ptrdiff_t kStep = 1 << 20;
  void report(const char* position) {
    progress_->advance(position - reported_);
    reported_ = position;
    next_ = position + kStep;
  }
  Progress* progress_;
  const char* reported_;
  const char* next_;
  const char* end_;
};

/// A cursor over text held in memory: blanks are spaces, tabs and carriage returns; a line ends at '\n', at the end
/// of the data or (when comments are on) at '#'. Numbers are parsed in place with std::from_chars.
class TextCursor {
 public:
  /// A cursor at the start of `data`, which is line `first_line` of the file `name` (for messages).
  TextCursor(std::string_view data, const std::string& name, bool hash_comments, long first_line = 1)
      : p_(data.data()), end_(data.data() + data.size()), line_(first_line), name_(name), comments_(hash_comments) {}

  /// Reports the bytes passed to `progress` as lines are read (nullptr: no reports).
  void set_progress(ByteProgress* progress) { progress_ = progress; }

  bool at_end() const { return p_ == end_; }
  long line() const { return line_; }
  const std::string& name() const { return name_; }
  [[noreturn]] void fail(const std::string& what) const { fail_at_line(name_, line_, what); }

  /// Skips spaces, tabs and carriage returns on the current line.
  void skip_blanks() {
    while (p_ != end_ && (*p_ == ' ' || *p_ == '\t' || *p_ == '\r')) ++p_;
  }
  /// True (after skipping blanks) when nothing but a comment is left on the current line.
  bool at_line_end() {
    skip_blanks();
    return p_ == end_ || *p_ == '\n' || (comments_ && *p_ == '#');
  }
  /// Moves to the start of the next line (skipping whatever is left on this one).
  void next_line() {
    const void* nl = std::memchr(p_, '\n', size_t(end_ - p_));
    if (nl == nullptr) {
      p_ = end_;
      return;
    }
    p_ = static_cast<const char*>(nl) + 1;
    ++line_;
    if (progress_ != nullptr) progress_->at(p_);
  }
  /// Requires the rest of the line to be empty, then moves to the next line.
  void end_line(const char* what) {
    if (!at_line_end()) fail(fmt::format("unexpected '{}' after {}", preview(), what));
    next_line();
  }
  /// Skips empty and comment-only lines.
  void skip_empty_lines() {
    while (!at_end() && at_line_end()) next_line();
  }
  /// The next run of non-blank characters on the current line (empty at the end of the line).
  std::string_view token() {
    if (at_line_end()) return {};
    const char* start = p_;
    while (p_ != end_ && *p_ != ' ' && *p_ != '\t' && *p_ != '\r' && *p_ != '\n') ++p_;
    return {start, size_t(p_ - start)};
  }
  /// The next character without consuming it ('\0' at the end).
  char peek() const { return p_ == end_ ? '\0' : *p_; }
  /// Consumes one character.
  void advance() { ++p_; }

  /// Parses a finite number on the current line. Throws "expected <what>".
  double number(const char* what) {
    double v;
    if (!try_number(v)) fail(fmt::format("expected {}, got '{}'", what, preview()));
    return v;
  }
  /// Parses a finite number if one follows on this line; false (nothing consumed) otherwise; NaN and infinity fail.
  bool try_number(double& v) {
    if (at_line_end()) return false;
    const char* start = p_ + (*p_ == '+' ? 1 : 0);
    const auto [next, ec] = std::from_chars(start, end_, v);
    if (ec != std::errc() || !ends_token(next)) return false;
    if (!std::isfinite(v))
      fail(fmt::format("expected a finite number, got '{}'", std::string_view(p_, size_t(next - p_))));
    p_ = next;
    return true;
  }
  /// Parses an integer on the current line (no blanks skipped when `immediate`). Throws "expected <what>".
  long long integer(const char* what, bool immediate = false) {
    if (!immediate && at_line_end()) fail(fmt::format("expected {}", what));
    long long v;
    const char* start = p_ != end_ && *p_ == '+' ? p_ + 1 : p_;
    const auto [next, ec] = std::from_chars(start, end_, v);
    if (ec != std::errc()) fail(fmt::format("expected {}, got '{}'", what, preview()));
    p_ = next;
    return v;
  }
  /// The rest of the current token, for messages (at most 40 characters, through printable()).
  std::string preview() const {
    const char* e = p_;
    while (e != end_ && e - p_ < 40 && *e != ' ' && *e != '\t' && *e != '\r' && *e != '\n') ++e;
    if (e == p_) return p_ == end_ ? "end of file" : "end of line";
    return printable(std::string_view(p_, size_t(e - p_)));
  }
  /// Bytes left.
  size_t remaining() const { return size_t(end_ - p_); }
  /// The current position in the buffer.
  const char* position() const { return p_; }

 private:
  bool ends_token(const char* q) const {
    return q == end_ || *q == ' ' || *q == '\t' || *q == '\r' || *q == '\n' || (comments_ && *q == '#');
  }

  const char* p_;
  const char* end_;
  long line_;
  const std::string& name_;
  bool comments_;
  ByteProgress* progress_ = nullptr;
};

/// Reads a scalar of type T stored at `p` in little (or big) endian byte order.
template <class T>
T load_scalar(const char* p, bool big_endian) {
  using U = std::conditional_t<
      sizeof(T) == 1, uint8_t,
      std::conditional_t<sizeof(T) == 2, uint16_t, std::conditional_t<sizeof(T) == 4, uint32_t, uint64_t>>>;
  U u;
  std::memcpy(&u, p, sizeof(U));
  if (big_endian != (std::endian::native == std::endian::big)) {
    if constexpr (sizeof(U) == 2) u = __builtin_bswap16(u);
    if constexpr (sizeof(U) == 4) u = __builtin_bswap32(u);
    if constexpr (sizeof(U) == 8) u = __builtin_bswap64(u);
  }
  return std::bit_cast<T>(u);
}

/// Appends the bytes of a little-endian scalar.
template <class T>
void store_le(std::string& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  if constexpr (std::endian::native == std::endian::big) std::reverse(bytes, bytes + sizeof(T));
  out.append(bytes, sizeof(T));
}

/// Appends formatted text to a buffer that is flushed to the stream in large blocks.
class BufferedWriter {
 public:
  explicit BufferedWriter(std::ostream& out) : out_(out) {}
  ~BufferedWriter() { flush(); }
  BufferedWriter(const BufferedWriter&) = delete;
  BufferedWriter& operator=(const BufferedWriter&) = delete;
  template <class... Args>
  void print(fmt::format_string<Args...> format, Args&&... args) {
    fmt::format_to(std::back_inserter(buffer_), format, std::forward<Args>(args)...);
    if (buffer_.size() > (1 << 20)) flush();
  }
  void flush() {
    out_.write(buffer_.data(), std::streamsize(buffer_.size()));
    buffer_.clear();
  }

 private:
  std::ostream& out_;
  fmt::memory_buffer buffer_;
};

}  // namespace tessera::mesh_io
