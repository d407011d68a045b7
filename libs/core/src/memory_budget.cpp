#include "tessera/core/memory_budget.hpp"

#include <unistd.h>

#include <atomic>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "tessera/core/parse.hpp"

namespace tessera {
namespace {

std::atomic<uint64_t> g_limit{0};  // 0: the default budget

std::optional<std::string> read_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) return std::nullopt;
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::optional<uint64_t> parse_unsigned(std::string_view text) {
  uint64_t value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

uint64_t physical_memory() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && page > 0 ? uint64_t(pages) * uint64_t(page) : std::numeric_limits<uint64_t>::max();
}

}  // namespace

std::optional<uint64_t> parse_cgroup_limit(std::string_view text) {
  const std::optional<uint64_t> value = parse_unsigned(trim(text));
  // cgroup v1 says "no limit" with a huge page-rounded number (0x7FFFFFFFFFFFF000); v2 says "max".
  if (!value || *value >= (uint64_t(1) << 62)) return std::nullopt;
  return value;
}

std::optional<uint64_t> parse_mem_available(std::string_view text) {
  for (std::string_view line : split(text, '\n')) {
    constexpr std::string_view kKey = "MemAvailable:";
    if (line.substr(0, kKey.size()) != kKey) continue;
    std::string_view rest = trim(line.substr(kKey.size()));
    if (rest.size() >= 2 && rest.substr(rest.size() - 2) == "kB") rest = trim(rest.substr(0, rest.size() - 2));
    if (const auto kib = parse_unsigned(rest)) return *kib * 1024;
    return std::nullopt;
  }
  return std::nullopt;
}

uint64_t usable_memory(const MemorySources& sources) {
  std::optional<uint64_t> limit;
  const auto take = [&](std::optional<uint64_t> v) {
    if (v && (!limit || *v < *limit)) limit = v;
  };
  if (const auto text = read_text(sources.cgroup_v2)) take(parse_cgroup_limit(*text));
  if (const auto text = read_text(sources.cgroup_v1)) take(parse_cgroup_limit(*text));
  if (const auto text = read_text(sources.meminfo)) take(parse_mem_available(*text));
  return limit ? *limit : physical_memory();
}

uint64_t MemoryBudget::default_bytes(const MemorySources& sources) {
  return uint64_t(double(usable_memory(sources)) * kDefaultFraction);
}

uint64_t MemoryBudget::bytes() {
  const uint64_t limit = g_limit.load();
  return limit != 0 ? limit : default_bytes();
}

void MemoryBudget::set_limit(uint64_t bytes) { g_limit.store(bytes); }

void MemoryBudget::check(uint64_t bytes, std::string_view what) {
  const uint64_t budget = MemoryBudget::bytes();
  if (bytes <= budget) return;
  throw MemoryBudgetError(fmt::format("{} needs about {}, the memory budget is {} (raise it with --max-memory SIZE)",
                                      what, format_bytes(bytes), format_bytes(budget)));
}

uint64_t parse_memory_size(std::string_view text, std::string_view what) {
  const std::string_view t = trim(text);
  size_t digits = 0;
  while (digits < t.size() && (std::isdigit(static_cast<unsigned char>(t[digits])) || t[digits] == '.')) ++digits;
  std::string suffix(t.substr(digits));
  for (char& c : suffix) c = char(std::toupper(static_cast<unsigned char>(c)));
  int shift = -1;
  if (suffix.empty() || suffix == "B") shift = 0;
  const std::string_view units = "KMGT";
  for (size_t i = 0; i < units.size(); ++i) {
    const std::string u(1, units[i]);
    if (suffix == u || suffix == u + "B" || suffix == u + "IB") shift = 10 * int(i + 1);
  }
  const auto invalid = [&] {
    return InvalidInput(
        fmt::format("{}: expected a memory size such as 512M or 4G (suffixes K, M, G, T; 1K = 1024), "
                    "got '{}'",
                    what, printable(text)));
  };
  double number = 0;
  const auto [end, ec] = std::from_chars(t.data(), t.data() + digits, number);
  if (digits == 0 || shift < 0 || ec != std::errc() || end != t.data() + digits) throw invalid();
  const double bytes = std::floor(std::ldexp(number, shift));
  if (!(bytes >= 1) || bytes >= std::ldexp(1.0, 64)) throw invalid();
  return uint64_t(bytes);
}

std::string format_bytes(uint64_t bytes) {
  if (bytes < 1024) return fmt::format("{} bytes", bytes);
  const char* units[] = {"KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  double value = double(bytes) / 1024;
  int unit = 0;
  while (value >= 1024 && unit < 5) value /= 1024, ++unit;
  return fmt::format("{:.1f} {}", value, units[unit]);
}

uint64_t saturating_product(std::initializer_list<uint64_t> factors) {
  uint64_t product = 1;
  for (const uint64_t f : factors) {
    if (f == 0) return 0;
    if (product > std::numeric_limits<uint64_t>::max() / f)
      product = std::numeric_limits<uint64_t>::max();
    else
      product *= f;
  }
  return product;
}

}  // namespace tessera
