// The scene loader's JSON stages (internal to the scene module): text to a document, and a document without keyed
// values to a Scene. animation.cpp evaluates keyed values in between.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "tessera/scene/scene.hpp"

namespace tessera::detail {

using Json = nlohmann::json;

/// Parses scene JSON text; throws InvalidInput "name: byte N: ..." for malformed JSON, and naming the path for a
/// duplicate key or objects and arrays nested deeper than 64 levels.
Json parse_scene_json(std::string_view text, const std::string& name);

/// The scene a document describes (keyed values already evaluated); throws InvalidInput naming the JSON path.
Scene scene_from_json(const Json& doc, const std::string& name, const std::filesystem::path& base_dir);

}  // namespace tessera::detail
