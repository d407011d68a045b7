#include "tessera/core/error.hpp"

namespace tessera {

std::string located(const std::string& where, const std::string& what) { return where + ": " + what; }

std::string at_line(const std::string& path, long line) { return fmt::format("{}:{}", path, line); }

std::string at_byte(const std::string& path, long long offset) {
  return fmt::format("{}: byte offset {}", path, offset);
}

namespace detail {
void check_failed(const char* file, int line, const char* expr, const std::string& operands) {
  std::string msg = fmt::format("internal check failed at {}:{}: {}", file, line, expr);
  if (!operands.empty()) msg += " (" + operands + ")";
  throw InternalError(msg);
}
}  // namespace detail

}  // namespace tessera
