#pragma once
// The memory budget: how many bytes one request (an image, a volume, a subdivided mesh, a decoded texture) may ask
// for before Tessera allocates it. Large-request sites estimate their bytes and call MemoryBudget::check, which
// refuses a request over the budget with the estimate and the budget in the message, instead of running into
// std::bad_alloc or the kernel's OOM killer.
//
// The default budget is a fraction of the memory this process may use: the smaller of the cgroup limit (v2
// memory.max, v1 memory.limit_in_bytes) and the available memory (MemAvailable in /proc/meminfo, else the physical
// memory). `--max-memory SIZE` replaces it (set_limit).
#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>

#include "tessera/core/error.hpp"

namespace tessera {

/// A request that needs more memory than the budget allows (an InvalidInput: the request is what is too large).
class MemoryBudgetError : public InvalidInput {
 public:
  using InvalidInput::InvalidInput;
};

/// Where the default budget reads its limits; the defaults are the real files, tests pass fake ones.
struct MemorySources {
  std::filesystem::path cgroup_v2 = "/sys/fs/cgroup/memory.max";
  std::filesystem::path cgroup_v1 = "/sys/fs/cgroup/memory/memory.limit_in_bytes";
  std::filesystem::path meminfo = "/proc/meminfo";
};

/// The process-wide memory budget.
class MemoryBudget {
 public:
  /// Share of the usable memory that the default budget allows one request (the rest is for the program, the
  /// input and what the estimates leave out).
  static constexpr double kDefaultFraction = 0.75;

  /// The budget in bytes: the limit given to set_limit, or default_bytes().
  static uint64_t bytes();
  /// Replaces the budget (--max-memory); 0 restores the default.
  static void set_limit(uint64_t bytes);
  /// kDefaultFraction of usable_memory(sources).
  static uint64_t default_bytes(const MemorySources& sources = {});
  /// Throws MemoryBudgetError "<what> needs about X, the memory budget is Y (--max-memory)" when bytes > bytes().
  static void check(uint64_t bytes, std::string_view what);
};

/// The memory this process may use: the smallest of the cgroup limit (v2 or v1) and MemAvailable; the physical
/// memory when neither file says anything.
uint64_t usable_memory(const MemorySources& sources = {});

/// Parses a cgroup limit file's text: a byte count, or nullopt for "max" (v2) and the v1 "no limit" values (at least
/// 2^62) and for anything unreadable.
std::optional<uint64_t> parse_cgroup_limit(std::string_view text);

/// MemAvailable from /proc/meminfo's text, in bytes; nullopt when absent.
std::optional<uint64_t> parse_mem_available(std::string_view text);

/// Parses a memory size: a byte count with an optional binary suffix K, M, G or T (also KB/KiB, ...; 1K = 1024),
/// e.g. "512M", "4G", "1.5G", "1000000". Throws InvalidInput naming `what` for anything else or for 0.
uint64_t parse_memory_size(std::string_view text, std::string_view what);

/// Formats a byte count for messages: "512 bytes", "1.5 KiB", "31.5 GiB".
std::string format_bytes(uint64_t bytes);

/// The product of the factors, saturated at UINT64_MAX (an estimate that overflows is over any budget).
uint64_t saturating_product(std::initializer_list<uint64_t> factors);

}  // namespace tessera
