#pragma once
// Tessera's error types and CHECK macros.
//
// What a user can cause (a malformed file, a bad option) is reported with a typed exception derived from
// tessera::Error that says where (file, line or byte offset) and what was expected. Broken invariants inside the
// library are reported by TESSERA_CHECK, which prints the failed expression and its operands.
#include <fmt/format.h>

#include <stdexcept>
#include <string>

namespace tessera {

/// Base of every exception Tessera throws; what() is one line, ready to print after "tessera: error: ".
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Input that breaks a documented precondition: a malformed file, a value out of range, a bad option.
class InvalidInput : public Error {
 public:
  using Error::Error;
};

/// A file that cannot be opened, read or written.
class IoError : public Error {
 public:
  using Error::Error;
};

/// A mesh whose connectivity does not allow the requested operation (non-manifold, not triangles, ...).
class TopologyError : public Error {
 public:
  using Error::Error;
};

/// An internal invariant failed: a bug in Tessera, not in the input.
class InternalError : public Error {
 public:
  using Error::Error;
};

/// Formats "where: what" for errors that point into a file, e.g. input_error("a.obj:12", "expected 3 floats").
std::string located(const std::string& where, const std::string& what);

/// "path:line" for messages about text files.
std::string at_line(const std::string& path, long line);

/// "path: byte offset N" for messages about binary files.
std::string at_byte(const std::string& path, long long offset);

namespace detail {
[[noreturn]] void check_failed(const char* file, int line, const char* expr, const std::string& operands);
}  // namespace detail

}  // namespace tessera

/// Throws tessera::InternalError naming the expression, file and line when cond is false.
#define TESSERA_CHECK(cond) \
  ((cond) ? (void)0 : ::tessera::detail::check_failed(__FILE__, __LINE__, #cond, std::string()))

#define TESSERA_CHECK_OP_(a, op, b)                                                     \
  do {                                                                                  \
    const auto& tessera_a_ = (a);                                                       \
    const auto& tessera_b_ = (b);                                                       \
    if (!(tessera_a_ op tessera_b_))                                                    \
      ::tessera::detail::check_failed(__FILE__, __LINE__, #a " " #op " " #b,            \
                                      fmt::format("{} vs {}", tessera_a_, tessera_b_)); \
  } while (false)

/// Binary checks that print both operands, as pbrt's CHECK_EQ and friends.
#define TESSERA_CHECK_EQ(a, b) TESSERA_CHECK_OP_(a, ==, b)
#define TESSERA_CHECK_NE(a, b) TESSERA_CHECK_OP_(a, !=, b)
#define TESSERA_CHECK_LT(a, b) TESSERA_CHECK_OP_(a, <, b)
#define TESSERA_CHECK_LE(a, b) TESSERA_CHECK_OP_(a, <=, b)
#define TESSERA_CHECK_GT(a, b) TESSERA_CHECK_OP_(a, >, b)
#define TESSERA_CHECK_GE(a, b) TESSERA_CHECK_OP_(a, >=, b)
