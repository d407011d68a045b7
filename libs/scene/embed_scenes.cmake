# cmake -DOUTPUT=header -DSCENES="a.json|b.json" -P embed_scenes.cmake: writes a header with a table of the built-in
# scenes {name (file stem), JSON text}.
set(body "#pragma once\n// Generated from scenes/*.json by embed_scenes.cmake; do not edit.\n")
string(APPEND body "namespace tessera::builtin {\nstruct EmbeddedScene {\n  const char* name;\n  const char* text;\n};\n")
string(APPEND body "inline constexpr EmbeddedScene kScenes[] = {\n")
string(REPLACE "|" ";" scene_files "${SCENES}")
foreach(file IN LISTS scene_files)
  get_filename_component(stem ${file} NAME_WE)
  file(READ ${file} text)
  string(APPEND body "    {\"${stem}\", R\"embedded(${text})embedded\"},\n")
endforeach()
string(APPEND body "};\n}  // namespace tessera::builtin\n")
file(WRITE ${OUTPUT} "${body}")
