#pragma once
// Mesh files: OBJ, PLY (ASCII, binary little and big endian), OFF (with the C/N/ST variants) and STL (ASCII and
// binary). One reader per format parses from a memory buffer (so fuzzers and tests need no files); read_mesh and
// write_mesh pick the format by extension and go through files. Writers are atomic.
//
// Readers throw InvalidInput naming the file and the line (text) or byte offset (binary) and what was expected;
// truncated and hostile input (counts larger than the file can hold, indices out of range, NaN or infinite numbers)
// is rejected before anything large is allocated. File access errors are IoError. Every reader can report the bytes it
// has parsed to a Progress (for files of millions of faces).
#include <filesystem>
#include <iosfwd>
#include <string>
#include <string_view>
#include <vector>

#include "tessera/mesh/poly_mesh.hpp"

namespace tessera {

class Progress;

/// The mesh file formats.
enum class MeshFormat { obj, ply, off, stl };

/// Options of the writers.
struct MeshWriteOptions {
  bool binary = true;  ///< PLY and STL: binary (PLY little endian) or ASCII; ignored by OBJ and OFF
  /// PLY: positions, normals and uvs as `double` instead of `float` (float32, what most tools read and write, is
  /// exact to about 7 digits: 0.1 micrometre on a 1 m model).
  bool double_precision = false;
};

/// The format named by a path's extension (.obj, .ply, .off, .stl, any case). Throws InvalidInput otherwise.
MeshFormat mesh_format_from_path(const std::filesystem::path& path);

/// Reads a mesh file, format by extension. Throws IoError (cannot read) or InvalidInput (malformed). When `progress`
/// is set, it counts the file's bytes (its total must be the file size, see read_mesh_with_progress).
PolyMesh read_mesh(const std::filesystem::path& path, Progress* progress = nullptr);
/// Parses a mesh held in memory; `name` is used in error messages; `progress` (total data.size()) counts the bytes
/// parsed.
PolyMesh read_mesh(std::string_view data, MeshFormat format, const std::string& name, Progress* progress = nullptr);
/// Reads a mesh file showing progress by bytes parsed (a Progress labelled "read <file name>", in the process's
/// Progress mode: a bar on a terminal, lines with --progress plain).
PolyMesh read_mesh_with_progress(const std::filesystem::path& path);

/// Writes a mesh file atomically, format by extension. Face-varying uvs and normals (texture seams) are written per
/// corner in OBJ; PLY and OFF hold per-vertex properties only, so their vertices are split where the corners differ
/// (split_seams in convert.hpp). What a format cannot hold at all is left out: see unsupported_properties.
void write_mesh(const std::filesystem::path& path, const PolyMesh& mesh, const MeshWriteOptions& options = {});
/// Writes a mesh in `format` to a stream.
void write_mesh(std::ostream& out, const PolyMesh& mesh, MeshFormat format, const MeshWriteOptions& options = {});

/// The properties of `mesh` that write_mesh leaves out in `format`, by name ("texture coordinates", "normals",
/// "vertex colors", "creases", "corners"): OBJ holds all of them; PLY and OFF everything but the subdivision tags;
/// STL positions only (facet normals are recomputed). Empty when nothing is lost.
std::vector<std::string> unsupported_properties(const PolyMesh& mesh, MeshFormat format);

/// OBJ: `v x y z [r g b]`, `vt u v`, `vn x y z`, `f` with v, v/vt, v//vn, v/vt/vn corners (1-based, negative =
/// relative to the end), OpenSubdiv's tags `t crease 2/1/0 v0 v1 s` and `t corner 1/1/0 v s` (0-based; chains of
/// n vertices with 1 or n-1 sharpnesses accepted), comments. o/g/s/usemtl/mtllib and the other statements of the
/// OBJ specification are ignored; an unknown statement is an error. uv and normal references become per-vertex
/// properties when every vertex always uses the same one, face-varying (corner_uvs/corner_normals) otherwise;
/// they are dropped when some corners have none.
PolyMesh read_obj(std::string_view data, const std::string& name, Progress* progress = nullptr);
/// Writes OBJ with shortest round-trip numbers: positions (and colors), uvs and normals per vertex or per corner,
/// faces, crease and corner tags.
void write_obj(std::ostream& out, const PolyMesh& mesh);

/// PLY 1.0: `vertex` properties x y z, nx ny nz, uv as s t / u v / texture_u texture_v, red green blue (integer
/// types scaled by their maximum, floats as is; an alpha is skipped); `face` list vertex_indices or vertex_index of
/// any count and index type. Unknown properties and elements are skipped (lists included).
PolyMesh read_ply(std::string_view data, const std::string& name, Progress* progress = nullptr);
/// Writes PLY: float (or double, options.double_precision) x y z, nx ny nz and s t (the name most readers know:
/// Blender, MeshLab, Open3D, trimesh), uchar red green blue, a uchar (or int, past 255) count and int indices per
/// face; binary little endian or ASCII (options.binary). Per-vertex properties only: see write_mesh.
void write_ply(std::ostream& out, const PolyMesh& mesh, const MeshWriteOptions& options = {});

/// OFF with the header variants [ST][C][N]OFF: vertex lines x y z [nx ny nz] [r g b [a]] [s t] (colors in [0, 1]
/// or 0..255), face lines n i0 ... in-1 [ignored face color]; `#` comments; counts may follow the keyword.
PolyMesh read_off(std::string_view data, const std::string& name, Progress* progress = nullptr);
/// Writes [ST][C][N]OFF with per-vertex normals, colors (r g b 1) and uvs when present.
void write_off(std::ostream& out, const PolyMesh& mesh);

/// STL, binary (recognized by its size, 84 + 50 n bytes) or ASCII (`solid` ... `endsolid`); vertices that are
/// bit-identical are welded, triangles that collapse are dropped, the stored facet normals are ignored.
PolyMesh read_stl(std::string_view data, const std::string& name, Progress* progress = nullptr);
/// Writes STL (binary or ASCII): polygons are triangulated, facet normals computed (E1 x E2 normalized).
void write_stl(std::ostream& out, const PolyMesh& mesh, bool binary = true);

}  // namespace tessera
