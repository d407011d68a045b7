#pragma once
// The optional shared data sets (../shared/data beside the checkout): tests that use them skip when absent.
#include <gtest/gtest.h>

#include <filesystem>

/// Declares `var` as the path of `relative` under the shared data folder, or skips the test when it is missing.
#define TESSERA_SHARED_FILE(var, relative)                                                   \
  const std::filesystem::path var = std::filesystem::path(TESSERA_SHARED_DATA) / (relative); \
  if (!std::filesystem::exists(var)) GTEST_SKIP() << "shared data not found: " << var
