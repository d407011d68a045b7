#include "tessera/volume/volume_io.hpp"

#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <sstream>

#include "tessera/core/atomic_file.hpp"
#include "tessera/core/memory_budget.hpp"
#include "tessera/core/parse.hpp"
#include "tessera/image/image_io.hpp"
#include "tessera/volume/procedural.hpp"

namespace tessera {
namespace {

template <class T>
Volume<T> decode_typed(std::string_view voxels, const RawLayout& layout) {
  Volume<T> v(layout.dims, T{}, layout.spacing, layout.origin);
  std::memcpy(v.voxels().data(), voxels.data(), v.voxel_count() * sizeof(T));
  const bool swap = (layout.endian == Endian::big) == (std::endian::native == std::endian::little);
  if (swap && sizeof(T) > 1)
    for (T& x : v.voxels()) {
      auto* b = reinterpret_cast<unsigned char*>(&x);
      std::reverse(b, b + sizeof(T));
    }
  return v;
}

/// Inflates gzip or zlib data, expecting `size` bytes out (more are ignored, fewer are an error).
std::string inflate_exact(std::string_view in, uint64_t size, const std::string& name, uint64_t offset) {
  if (size > UINT32_MAX || in.size() > UINT32_MAX)
    throw InvalidInput(fmt::format("{}: gzip data over 4 GiB is not supported", name));
  // Deflate compresses at most about 1032:1, so a header asking for more than that is hostile (no huge allocation).
  if (size > 1032 * uint64_t(in.size()) + 64)
    throw InvalidInput(
        fmt::format("{}: {} bytes of gzip data at byte offset {} cannot hold the {} bytes the header says", name,
                    in.size(), offset, size));
  std::string out(size_t(size), '\0');
  z_stream zs{};
  if (inflateInit2(&zs, 15 + 32) != Z_OK) throw InvalidInput(fmt::format("{}: zlib initialization failed", name));
  zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(in.data()));
  zs.avail_in = uInt(in.size());
  zs.next_out = reinterpret_cast<Bytef*>(out.data());
  zs.avail_out = uInt(size);
  const int rc = inflate(&zs, Z_FINISH);
  const uint64_t produced = zs.total_out;
  inflateEnd(&zs);
  if (rc != Z_STREAM_END && rc != Z_BUF_ERROR)
    throw InvalidInput(fmt::format("{}: corrupt gzip data at byte offset {} (zlib error {})", name, offset, rc));
  if (produced < size)
    throw InvalidInput(fmt::format("{}: gzip data at byte offset {} inflates to {} bytes, the header says {}", name,
                                   offset, produced, size));
  return out;
}

uint64_t byte_count(const RawLayout& layout) { return checked_voxel_count(layout.dims) * voxel_size(layout.type); }

// Refuses, before the voxel data is read, a volume that needs more than the memory budget: 8 bytes a voxel, whatever
// its type, the most of the file's voxel bytes (or the inflated gzip data) with the volume built from them (2 x 4 for
// float32), the volume with the float copy that every computation makes (to_float: 4 + 4 at most), and the float
// volume with the copy of its values that profiling sorts (Otsu's threshold and percentiles: 4 + 4; the iso value,
// transfer function and `volume info` of every command that is not given them). Also rejects bad dims.
void check_voxel_memory(const RawLayout& layout, const std::string& name) {
  MemoryBudget::check(saturating_product({checked_voxel_count(layout.dims), 8}),
                      fmt::format("{}: reading {}x{}x{} {} voxels", name, layout.dims.x, layout.dims.y, layout.dims.z,
                                  voxel_type_name(layout.type)));
}

Vec3 parse_vector3(std::string_view text, const std::string& where) {
  std::string cleaned(text);
  for (char& c : cleaned)
    if (c == '(' || c == ')' || c == ',') c = ' ';
  std::istringstream in(cleaned);
  std::string a, b, c;
  if (!(in >> a >> b >> c))
    throw InvalidInput(located(where, fmt::format("expected 3 numbers, got '{}'", printable(text))));
  return {parse_double(a, where), parse_double(b, where), parse_double(c, where)};
}

std::vector<std::string> words(std::string_view text) {
  std::istringstream in{std::string(text)};
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

glm::ivec3 parse_dims(const std::vector<std::string>& w, const std::string& where) {
  if (w.size() != 3) throw InvalidInput(located(where, fmt::format("expected 3 sizes, got {}", w.size())));
  glm::ivec3 d;
  for (int i = 0; i < 3; ++i) {
    const long long s = parse_int(w[size_t(i)], where);
    if (s < 1 || s > (1LL << 30)) throw InvalidInput(located(where, fmt::format("size {} is out of range", s)));
    d[i] = int(s);
  }
  try {
    checked_voxel_count(d);
  } catch (const InvalidInput& e) {
    throw InvalidInput(located(where, e.what()));  // the header line that declares them
  }
  return d;
}

// A data file that a header names, for messages: its name is input like any other line of the header (control
// bytes, 10 KB of it), so it is quoted through printable(), a little longer than a value for a real path to fit.
constexpr size_t kShownPathChars = 200;
std::string shown_path(const std::filesystem::path& path) { return printable(path.string(), kShownPathChars); }

// read_file() for a data file that the header `header` names: its messages quote the path raw, so here they quote
// shown_path(), after the header's name. Only a regular file (or a link to one) is read: a header naming a device
// (/dev/zero: read until memory ran out) or a FIFO (a hang) is refused before the file is opened. A header's data
// has a size its sizes and type say, which only a regular file can be checked against; a volume from a pipe is read
// as a header with attached data (NRRD) or as a raw file named on the command line.
std::string read_data_file(const std::filesystem::path& path, const std::string& header) {
  // A missing file or a folder is read_file's error (it names them).
  using std::filesystem::file_type;
  std::error_code error;
  const file_type type = std::filesystem::status(path, error).type();
  const char* kind = type == file_type::fifo        ? "a FIFO"
                     : type == file_type::character ? "a character device"
                     : type == file_type::block     ? "a block device"
                     : type == file_type::socket    ? "a socket"
                                                    : nullptr;
  if (kind)
    throw IoError(fmt::format("{}: data file '{}' is {}: a header's data file must be a regular file", header,
                              shown_path(path), kind));
  try {
    return read_file(path);
  } catch (const IoError& e) {
    std::string message = e.what();
    const std::string raw = path.string(), shown = shown_path(path);
    if (!raw.empty())
      for (size_t at = message.find(raw); at != std::string::npos; at = message.find(raw, at + shown.size()))
        message.replace(at, raw.size(), shown);
    throw IoError(fmt::format("{}: {}", header, message));
  }
}

// read_raw() of a data file that the header `header` names, quoted as shown_path() in every message.
AnyVolume read_named_raw(const std::filesystem::path& path, const RawLayout& layout, const std::string& header) {
  const std::string name = shown_path(path);
  check_voxel_memory(layout, name);
  return decode_raw(read_data_file(path, header), layout, name);
}

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace

AnyVolume decode_raw(std::string_view bytes, const RawLayout& layout, const std::string& name) {
  const uint64_t need = byte_count(layout);
  if (layout.header_skip > bytes.size() || bytes.size() - layout.header_skip < need)
    throw InvalidInput(
        fmt::format("{}: file is too short: {}x{}x{} {} voxels need {} bytes from byte offset {}, the file "
                    "has {} bytes",
                    name, layout.dims.x, layout.dims.y, layout.dims.z, voxel_type_name(layout.type), need,
                    layout.header_skip, bytes.size()));
  // The box must be finite: spacings near DBL_MAX put the far corner at infinity, and every mesh vertex or ray
  // distance computed from it would be too.
  const Vec3 far = layout.origin + layout.spacing * Vec3(layout.dims - 1);
  for (int a = 0; a < 3; ++a)
    if (!std::isfinite(layout.origin[a]) || !std::isfinite(layout.spacing[a]) || !std::isfinite(far[a]))
      throw InvalidInput(
          fmt::format("{}: origin ({}, {}, {}) and spacing ({}, {}, {}) put the volume's box beyond the "
                      "finite numbers",
                      name, layout.origin.x, layout.origin.y, layout.origin.z, layout.spacing.x, layout.spacing.y,
                      layout.spacing.z));
  const std::string_view voxels = bytes.substr(size_t(layout.header_skip));
  switch (layout.type) {
    case VoxelType::uint8:
      return decode_typed<uint8_t>(voxels, layout);
    case VoxelType::uint16:
      return decode_typed<uint16_t>(voxels, layout);
    case VoxelType::int16:
      return decode_typed<int16_t>(voxels, layout);
    case VoxelType::float32: {
      // NaN or infinite voxels would reach value ranges, transfer functions and mesh vertices (NaN output, exit 0).
      Volume<float> v = decode_typed<float>(voxels, layout);
      const auto bad = std::find_if(v.voxels().begin(), v.voxels().end(), [](float x) { return !std::isfinite(x); });
      if (bad != v.voxels().end()) {
        const size_t i = size_t(bad - v.voxels().begin());
        const size_t nx = size_t(layout.dims.x), nxy = nx * size_t(layout.dims.y);
        throw InvalidInput(fmt::format(
            "{}: voxel ({}, {}, {}) at byte offset {} is {}: float volumes must hold finite "
            "values",
            name, i % nx, i / nx % size_t(layout.dims.y), i / nxy, layout.header_skip + i * sizeof(float), *bad));
      }
      return v;
    }
  }
  throw InvalidInput(fmt::format("{}: unknown voxel type", name));
}

AnyVolume read_raw(const std::filesystem::path& path, const RawLayout& layout) {
  check_voxel_memory(layout, path.string());  // bad dims and requests over the budget, before reading
  return decode_raw(read_file(path), layout, path.string());
}

AnyVolume parse_nrrd(std::string_view data, const std::string& name, const std::filesystem::path& base_dir) {
  if (data.substr(0, 7) != "NRRD000") throw InvalidInput(located(at_line(name, 1), "expected the magic 'NRRD000x'"));
  RawLayout layout;
  std::string encoding = "raw", data_file;
  bool have_type = false, have_sizes = false, have_endian = false;
  int dimension = 0;
  size_t pos = data.find('\n');
  if (pos == std::string_view::npos) throw InvalidInput(located(at_line(name, 1), "the header has no end"));
  ++pos;
  long line_no = 1;
  bool attached = false;
  while (pos < data.size()) {
    ++line_no;
    size_t end = data.find('\n', pos);
    if (end == std::string_view::npos) end = data.size();
    std::string_view line = data.substr(pos, end - pos);
    pos = end + 1;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (line.empty()) {
      attached = true;
      break;
    }
    if (line[0] == '#') continue;
    if (line.find(":=") != std::string_view::npos) continue;  // key/value pairs
    const size_t colon = line.find(": ");
    const std::string where = at_line(name, line_no);
    if (colon == std::string_view::npos)
      throw InvalidInput(located(where, fmt::format("expected 'field: value', got '{}'", printable(line))));
    const std::string field = lower(std::string(trim(line.substr(0, colon))));
    const std::string_view value = trim(line.substr(colon + 2));
    if (field == "type") {
      try {
        layout.type = parse_voxel_type(lower(std::string(value)));
      } catch (const InvalidInput&) {
        throw InvalidInput(
            located(where, fmt::format("unsupported type '{}' (uchar, ushort, short, float)", printable(value))));
      }
      have_type = true;
    } else if (field == "dimension") {
      dimension = int(parse_int(value, where));
      if (dimension != 3)
        throw InvalidInput(located(where, fmt::format("only 3D volumes are supported, got dimension {}", dimension)));
    } else if (field == "sizes") {
      layout.dims = parse_dims(words(value), where);
      have_sizes = true;
    } else if (field == "encoding") {
      encoding = lower(std::string(value));
      if (encoding == "gz") encoding = "gzip";
      if (encoding != "raw" && encoding != "gzip")
        throw InvalidInput(located(where, fmt::format("unsupported encoding '{}' (raw, gzip)", printable(value))));
    } else if (field == "endian") {
      const std::string e = lower(std::string(value));
      if (e != "little" && e != "big")
        throw InvalidInput(located(where, fmt::format("endian must be little or big, got '{}'", printable(value))));
      layout.endian = e == "big" ? Endian::big : Endian::little;
      have_endian = true;
    } else if (field == "spacings") {
      const auto w = words(value);
      if (w.size() != 3) throw InvalidInput(located(where, "expected 3 spacings"));
      for (int i = 0; i < 3; ++i) {
        layout.spacing[i] = w[size_t(i)] == "nan" ? 1.0 : parse_double(w[size_t(i)], where);
        if (!(layout.spacing[i] > 0)) throw InvalidInput(located(where, "spacings must be positive"));
      }
    } else if (field == "space directions") {
      std::string v(value);
      for (int i = 0; i < 3; ++i) {
        const size_t open = v.find('('), close = v.find(')');
        if (open == std::string::npos || close == std::string::npos || close < open)
          throw InvalidInput(located(where, "expected three '(x,y,z)' vectors"));
        layout.spacing[i] = glm::length(parse_vector3(v.substr(open, close - open + 1), where));
        if (!(layout.spacing[i] > 0)) throw InvalidInput(located(where, "space directions must be non-zero"));
        v = v.substr(close + 1);
      }
    } else if (field == "space origin") {
      layout.origin = parse_vector3(value, where);
    } else if (field == "byte skip") {
      const long long skip = parse_int(value, where);
      if (skip < 0) throw InvalidInput(located(where, "byte skip -1 is not supported"));
      layout.header_skip = uint64_t(skip);
    } else if (field == "data file" || field == "datafile") {
      data_file = std::string(value);
    }
  }
  if (!have_type || !have_sizes || dimension != 3)
    throw InvalidInput(located(name, "the header needs type, dimension: 3 and sizes"));
  if (!have_endian && voxel_size(layout.type) > 1 && encoding != "ascii")
    throw InvalidInput(located(name, "the header needs endian for multi-byte voxels"));
  check_voxel_memory(layout, name);
  std::string detached;
  std::string_view payload;
  uint64_t payload_offset = pos;
  if (!data_file.empty()) {
    if (base_dir.empty()) throw InvalidInput(located(name, "detached data files are not allowed here"));
    detached = read_data_file(base_dir / data_file, name);
    payload = detached;
    payload_offset = 0;
  } else {
    if (!attached) throw InvalidInput(located(name, "no blank line before the data and no data file"));
    payload = data.substr(std::min(pos, data.size()));
  }
  const std::string data_name = data_file.empty() ? name : shown_path(base_dir / data_file);
  if (encoding == "gzip") {
    if (layout.header_skip > payload.size())
      throw InvalidInput(
          fmt::format("{}: byte skip {} is past the end ({} bytes)", data_name, layout.header_skip, payload.size()));
    const std::string raw = inflate_exact(payload.substr(size_t(layout.header_skip)), byte_count(layout), data_name,
                                          payload_offset + layout.header_skip);
    RawLayout inner = layout;
    inner.header_skip = 0;
    return decode_raw(raw, inner, data_name);
  }
  // Data beyond what the sizes and type say means the header does not describe the file (a wrong type or size): refused
  // rather than read in part. (A short file is decode_raw's error.)
  const uint64_t need = byte_count(layout);
  if (layout.header_skip <= payload.size() && payload.size() - layout.header_skip > need)
    throw InvalidInput(
        fmt::format("{}: the data holds {} bytes from byte offset {}, more than the {} bytes that the "
                    "header's sizes and type say",
                    data_name, payload.size() - layout.header_skip, payload_offset + layout.header_skip, need));
  try {
    return decode_raw(payload, layout, data_name);
  } catch (const InvalidInput& e) {
    throw InvalidInput(fmt::format("{} (data starts at byte offset {})", e.what(), payload_offset));
  }
}

AnyVolume read_nrrd(const std::filesystem::path& path) {
  return parse_nrrd(read_file(path), path.string(), path.parent_path().empty() ? "." : path.parent_path());
}

AnyVolume read_mhd(const std::filesystem::path& path) {
  const std::string text = read_file(path);
  const std::string name = path.string();
  RawLayout layout;
  std::string data_file;
  bool have_dims = false, have_type = false;
  std::istringstream in(text);
  long line_no = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    const std::string where = at_line(name, line_no);
    const size_t eq = line.find('=');
    if (trim(line).empty()) continue;
    if (eq == std::string::npos)
      throw InvalidInput(located(where, fmt::format("expected 'Key = Value', got '{}'", printable(line))));
    const std::string key(trim(std::string_view(line).substr(0, eq)));
    const std::string value(trim(std::string_view(line).substr(eq + 1)));
    if (key == "NDims") {
      if (parse_int(value, where) != 3) throw InvalidInput(located(where, "only NDims = 3 is supported"));
    } else if (key == "DimSize") {
      layout.dims = parse_dims(words(value), where);
      have_dims = true;
    } else if (key == "ElementType") {
      static const std::pair<const char*, VoxelType> kTypes[] = {{"MET_UCHAR", VoxelType::uint8},
                                                                 {"MET_USHORT", VoxelType::uint16},
                                                                 {"MET_SHORT", VoxelType::int16},
                                                                 {"MET_FLOAT", VoxelType::float32}};
      const auto it =
          std::find_if(std::begin(kTypes), std::end(kTypes), [&](const auto& t) { return value == t.first; });
      if (it == std::end(kTypes))
        throw InvalidInput(located(where, fmt::format("unsupported ElementType '{}'", printable(value))));
      layout.type = it->second;
      have_type = true;
    } else if (key == "ElementSpacing" || key == "ElementSize") {
      layout.spacing = parse_vector3(value, where);
      if (!(layout.spacing.x > 0 && layout.spacing.y > 0 && layout.spacing.z > 0))
        throw InvalidInput(located(where, "spacing must be positive"));
    } else if (key == "Offset" || key == "Origin" || key == "Position") {
      layout.origin = parse_vector3(value, where);
    } else if (key == "ElementByteOrderMSB" || key == "BinaryDataByteOrderMSB") {
      layout.endian = lower(value) == "true" ? Endian::big : Endian::little;
    } else if (key == "HeaderSize") {
      const long long skip = parse_int(value, where);
      if (skip < 0) throw InvalidInput(located(where, "HeaderSize -1 is not supported"));
      layout.header_skip = uint64_t(skip);
    } else if (key == "CompressedData") {
      if (lower(value) == "true") throw InvalidInput(located(where, "compressed MetaImage data is not supported"));
    } else if (key == "ElementDataFile") {
      if (value == "LOCAL") throw InvalidInput(located(where, "ElementDataFile = LOCAL is not supported"));
      data_file = value;
    }
  }
  if (!have_dims || !have_type || data_file.empty())
    throw InvalidInput(located(name, "the header needs DimSize, ElementType and ElementDataFile"));
  return read_named_raw(path.parent_path() / data_file, layout, name);
}

Volume<uint8_t> read_slices(const std::vector<std::filesystem::path>& files, const Vec3& spacing) {
  if (files.empty()) throw InvalidInput("a slice stack needs at least one image");
  if (files.size() > size_t(1) << 30)
    throw InvalidInput(
        fmt::format("a slice stack of {} images is more than the {} a volume holds", files.size(), 1 << 30));
  Volume<uint8_t> v;
  for (size_t z = 0; z < files.size(); ++z) {
    const ImageRGBA image = read_image(files[z]);  // the reader refuses one slice over the budget from its header
    if (z == 0) {
      // The whole stack, estimated from the first slice before the others are decoded (each fits the budget alone,
      // their volume may not): a byte per voxel, and the slice being decoded (at most 32 bytes a pixel: a 16-bit
      // or HDR decoder's samples and the float RGBA image).
      const uint64_t pixels = uint64_t(image.width()) * uint64_t(image.height());
      MemoryBudget::check(saturating_product({pixels, files.size()}) + saturating_product({pixels, 32}),
                          fmt::format("{}: a stack of {} slices of {}x{} pixels", shown_path(files[0]), files.size(),
                                      image.width(), image.height()));
      v = Volume<uint8_t>(glm::ivec3(image.width(), image.height(), int(files.size())), 0, spacing);
    }
    if (image.width() != v.dims().x || image.height() != v.dims().y)
      throw InvalidInput(fmt::format("{}: slice is {}x{}, the first slice is {}x{}", files[z].string(), image.width(),
                                     image.height(), v.dims().x, v.dims().y));
    for (int y = 0; y < image.height(); ++y)
      for (int x = 0; x < image.width(); ++x) {
        const auto& p = image(x, y);
        v(x, y, int(z)) = uint8_t(std::lround(std::clamp((p.x + p.y + p.z) / 3.0f, 0.0f, 1.0f) * 255.0f));
      }
  }
  return v;
}

AnyVolume read_volume(const std::string& name, const RawLayout& raw) {
  Volume<float> procedural;
  if (!std::filesystem::exists(name) && make_procedural(name, procedural)) return procedural;
  const std::string ext = lower(std::filesystem::path(name).extension().string());
  if (ext == ".nrrd" || ext == ".nhdr") return read_nrrd(name);
  if (ext == ".mhd") return read_mhd(name);
  if (raw.dims.x <= 0) throw InvalidInput(fmt::format("{}: a raw volume needs --dims X,Y,Z (and --dtype)", name));
  return read_raw(name, raw);
}

namespace {

std::string voxel_bytes(const AnyVolume& volume, Endian endian) {
  return std::visit(
      [&](const auto& v) {
        using T = typename std::decay_t<decltype(v)>::Value;
        std::string bytes(v.voxel_count() * sizeof(T), '\0');
        std::memcpy(bytes.data(), v.voxels().data(), bytes.size());
        if ((endian == Endian::big) == (std::endian::native == std::endian::little) && sizeof(T) > 1)
          for (size_t i = 0; i < bytes.size(); i += sizeof(T))
            std::reverse(bytes.begin() + long(i), bytes.begin() + long(i + sizeof(T)));
        return bytes;
      },
      volume);
}

std::string gzip(const std::string& in) {
  z_stream zs{};
  if (deflateInit2(&zs, Z_DEFAULT_COMPRESSION, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) != Z_OK)
    throw IoError("zlib initialization failed");
  std::string out(deflateBound(&zs, uLong(in.size())), '\0');
  zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(in.data()));
  zs.avail_in = uInt(in.size());
  zs.next_out = reinterpret_cast<Bytef*>(out.data());
  zs.avail_out = uInt(out.size());
  const int rc = deflate(&zs, Z_FINISH);
  out.resize(zs.total_out);
  deflateEnd(&zs);
  if (rc != Z_STREAM_END) throw IoError("gzip compression failed");
  return out;
}

}  // namespace

void write_raw(const std::filesystem::path& path, const AnyVolume& volume, Endian endian) {
  write_file_atomic(path, voxel_bytes(volume, endian));
}

void write_nrrd(const std::filesystem::path& path, const AnyVolume& volume, bool use_gzip) {
  static const char* kNrrdType[] = {"uchar", "ushort", "short", "float"};
  const glm::ivec3 d = dims_of(volume);
  const Vec3 s = spacing_of(volume), o = origin_of(volume);
  const bool detached = lower(path.extension().string()) == ".nhdr";
  const bool gz = use_gzip && !detached;
  std::string header = fmt::format(
      "NRRD0004\n# written by Tessera\ntype: {}\ndimension: 3\nsizes: {} {} {}\nendian: little\nencoding: {}\n"
      "space dimension: 3\nspace directions: ({},0,0) (0,{},0) (0,0,{})\nspace origin: ({},{},{})\n",
      kNrrdType[volume.index()], d.x, d.y, d.z, gz ? "gzip" : "raw", s.x, s.y, s.z, o.x, o.y, o.z);
  const std::string bytes = voxel_bytes(volume, Endian::little);
  if (detached) {
    const auto data_path = std::filesystem::path(path).replace_extension(".raw");
    write_file_atomic(data_path, bytes);
    write_file_atomic(path, header + fmt::format("data file: {}\n", data_path.filename().string()));
  } else {
    write_file_atomic(path, header + "\n" + (gz ? gzip(bytes) : bytes));
  }
}

}  // namespace tessera
