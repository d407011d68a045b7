// The built-in scenes, embedded from scenes/*.json at build time.
#include <algorithm>
#include <filesystem>

#include "builtin_scenes.hpp"
#include "tessera/core/error.hpp"
#include "tessera/scene/scene.hpp"

namespace tessera {

std::vector<std::string> builtin_scene_names() {
  std::vector<std::string> names;
  for (const auto& s : builtin::kScenes) names.emplace_back(s.name);
  std::sort(names.begin(), names.end());
  return names;
}

std::string_view builtin_scene_text(const std::string& name) {
  for (const auto& s : builtin::kScenes)
    if (name == s.name) return s.text;
  std::string list;
  for (const auto& n : builtin_scene_names()) list += (list.empty() ? "" : ", ") + n;
  throw InvalidInput(fmt::format("'{}' is neither a scene file nor a built-in scene ({})", name, list));
}

Scene builtin_scene(const std::string& name) {
  // Built-in scenes use generated meshes only, so the base folder is never read.
  return parse_scene(builtin_scene_text(name), name, std::filesystem::path());
}

Scene load_scene_or_builtin(const std::string& name_or_path) {
  if (std::filesystem::exists(name_or_path)) return load_scene(name_or_path);
  return builtin_scene(name_or_path);
}

}  // namespace tessera
