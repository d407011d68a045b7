#pragma once
// What `tessera gallery` and `tessera demo` share: the --data option and the summary line's note on stand-ins.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <string>

#include "gallery.hpp"

namespace tessera::cli {

/// Adds --data DIR (an existing folder) to a command that draws pictures from the shared data sets.
inline void add_data_option(CLI::App& cmd, std::string& data) {
  cmd.add_option("--data", data,
                 "Folder of the shared data sets (default: $TESSERA_DATA, $TESSERA_SHARED_DATA, ./shared/data, "
                 "../shared/data, shared/data above the executable, the build's folder)")
      ->check(CLI::ExistingDirectory);
}

/// The summary line's tail: where the data came from, and how many stand-ins were drawn for missing files.
inline std::string stand_in_note(const examples::RunSummary& run, const examples::DataFolder& data) {
  if (run.stand_ins == 0) return "";
  return fmt::format(" ({} stand-in(s) for missing shared data{}; see the warnings above)", run.stand_ins,
                     data.dir.empty() ? ": no data folder found" : " in " + data.dir.string());
}

}  // namespace tessera::cli
