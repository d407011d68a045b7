#pragma once
// The .bpt Bezier patch text format (DESIGN.md section 5; data/MANIFEST.md "Bezier patches"): the patch count, then
// per patch a line "3 3" (the u and v degrees) and 16 lines "x y z", control point k = 4 i + j. Tokens are separated
// by any white space; nothing else (no comments) is allowed.
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "tessera/curves/bezier_patch.hpp"

namespace tessera {

/// Parses .bpt text. `name` labels errors. Strict: throws InvalidInput "name:LINE: <what was expected>, got '<token>'"
/// for a malformed or missing number, degrees other than 3 3, a negative count, a count the text is too short to hold
/// (rejected before any allocation), non-finite coordinates, or anything after the last patch.
std::vector<BezierPatch> parse_bpt(std::string_view text, const std::string& name = "<bpt>");

/// Reads a .bpt file. Throws IoError when it cannot be read, InvalidInput (naming the file and line) when malformed.
std::vector<BezierPatch> read_bpt(const std::filesystem::path& path);

/// The .bpt text of `patches`, with shortest round-trip number formatting (parse_bpt gives the same doubles back).
std::string format_bpt(std::span<const BezierPatch> patches);

/// Writes a .bpt file atomically. Throws IoError.
void write_bpt(const std::filesystem::path& path, std::span<const BezierPatch> patches);

}  // namespace tessera
