#pragma once
// Volume files: raw voxels (with the layout given by the caller), NRRD (.nrrd attached, .nhdr detached; raw and gzip
// encodings), MetaImage (.mhd + raw data file), a stack of 2D slice images, and procedural names ("sphere:64").
//
// Readers check every size against the bytes present before allocating: a header whose sizes overflow or a file
// shorter than its header says gives InvalidInput naming the file and the line or byte offset.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "tessera/volume/volume.hpp"

namespace tessera {

enum class Endian { little, big };

/// How raw voxels are laid out (what --dims, --dtype, --endian, --spacing and --header-skip say).
struct RawLayout {
  glm::ivec3 dims{0};  ///< voxels along x, y, z (x fastest)
  VoxelType type = VoxelType::uint8;
  Endian endian = Endian::little;
  Vec3 spacing{1.0};
  Vec3 origin{0.0};
  uint64_t header_skip = 0;  ///< bytes before the first voxel
};

/// Decodes voxels from `bytes` (the whole file; the voxels start at layout.header_skip). `name` is used in messages.
/// Throws InvalidInput when the bytes are fewer than the layout needs (extra trailing bytes are ignored), when a float
/// voxel is NaN or infinite (naming the voxel and its byte offset), or when origin and spacing put the box's far
/// corner beyond the finite numbers. Every reader below decodes through it.
AnyVolume decode_raw(std::string_view bytes, const RawLayout& layout, const std::string& name);
/// Reads a raw file. Throws IoError when it cannot be read, InvalidInput as decode_raw.
AnyVolume read_raw(const std::filesystem::path& path, const RawLayout& layout);

/// Parses an NRRD file held in memory (NRRD0001-0005: type, dimension 3, sizes, encoding raw|gzip, endian, spacings or
/// a diagonal space directions, space origin, byte skip). Detached data files are resolved against `base_dir`; an
/// empty base_dir refuses them (the fuzz target's mode). Throws InvalidInput with "name:line" or a byte offset.
AnyVolume parse_nrrd(std::string_view data, const std::string& name, const std::filesystem::path& base_dir = {});
/// Reads a .nrrd or .nhdr file.
AnyVolume read_nrrd(const std::filesystem::path& path);

/// Reads a MetaImage .mhd header (NDims 3, DimSize, ElementType MET_UCHAR|MET_USHORT|MET_SHORT|MET_FLOAT,
/// ElementSpacing, Offset, ElementByteOrderMSB, HeaderSize, ElementDataFile) and its raw data file.
AnyVolume read_mhd(const std::filesystem::path& path);

/// Stacks 2D slice images (PNG, PGM, ... as read_image reads them; gray = mean of r, g, b) into a uint8 volume, one
/// z layer per file in the given order, as the notes' slice data. Throws InvalidInput when sizes differ or none given.
Volume<uint8_t> read_slices(const std::vector<std::filesystem::path>& files, const Vec3& spacing = Vec3(1.0));

/// Reads a volume by name: a procedural spec ("sphere:64"), .nrrd/.nhdr, .mhd, or else raw voxels laid out by `raw`
/// (which must then have dims). Throws InvalidInput when a raw file has no dims.
AnyVolume read_volume(const std::string& name, const RawLayout& raw = {});

/// Writes the voxels as raw bytes in the given byte order (atomically).
void write_raw(const std::filesystem::path& path, const AnyVolume& volume, Endian endian = Endian::little);
/// Writes NRRD atomically: a ".nhdr" path gets a detached header plus "<stem>.raw" beside it; any other path gets an
/// attached header. `gzip` selects the gzip encoding (attached only).
void write_nrrd(const std::filesystem::path& path, const AnyVolume& volume, bool gzip = false);

}  // namespace tessera
