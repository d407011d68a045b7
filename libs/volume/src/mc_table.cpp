#include "tessera/volume/mc_table.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "tessera/core/error.hpp"

namespace tessera::mc {
namespace {

/// Outward normals of the faces, in the order of faces().
constexpr std::array<glm::ivec3, 6> kFaceNormals{{{0, 0, -1}, {0, 0, 1}, {0, -1, 0}, {0, 1, 0}, {-1, 0, 0}, {1, 0, 0}}};

int edge_between(int a, int b) {
  for (int e = 0; e < 12; ++e)
    if ((edges()[e][0] == a && edges()[e][1] == b) || (edges()[e][0] == b && edges()[e][1] == a)) return e;
  return -1;
}

Vec3 edge_midpoint(int e) {
  return 0.5 * (Vec3(corners()[size_t(edges()[e][0])]) + Vec3(corners()[size_t(edges()[e][1])]));
}

bool inside(int cube_case, int corner) { return (cube_case >> corner) & 1; }

/// The face segments of a case, each oriented (a -> b) so that cross(b - a, n) points toward the inside corners.
std::vector<std::array<int, 3>> face_segments(int cube_case, int join) {
  std::vector<std::array<int, 3>> segments;  // (from edge, to edge, face)
  for (int f = 0; f < 6; ++f) {
    const auto& q = faces()[size_t(f)];
    std::vector<std::array<int, 2>> pairs;
    const bool ambiguous = (ambiguous_faces(cube_case) >> f) & 1;
    if (!ambiguous) {
      std::vector<int> crossing;
      for (int i = 0; i < 4; ++i)
        if (inside(cube_case, q[size_t(i)]) != inside(cube_case, q[size_t((i + 1) % 4)]))
          crossing.push_back(edge_between(q[size_t(i)], q[size_t((i + 1) % 4)]));
      if (crossing.size() == 2) pairs.push_back({crossing[0], crossing[1]});
    } else {
      // Cut off the corners of one state: the inside corners (separated) or the outside ones (joined).
      const bool cut_inside = !((join >> f) & 1);
      for (int i = 0; i < 4; ++i)
        if (inside(cube_case, q[size_t(i)]) == cut_inside)
          pairs.push_back({edge_between(q[size_t((i + 3) % 4)], q[size_t(i)]), edge_between(q[size_t(i)], q[size_t((i + 1) % 4)])});
    }
    for (auto [a, b] : pairs) {
      // The inside end of edge a lies on the inside side of the segment.
      const int ca = edges()[size_t(a)][0], cb = edges()[size_t(a)][1];
      const Vec3 p_in = Vec3(corners()[size_t(inside(cube_case, ca) ? ca : cb)]);
      const Vec3 pa = edge_midpoint(a), pb = edge_midpoint(b);
      if (glm::dot(glm::cross(pb - pa, Vec3(kFaceNormals[size_t(f)])), p_in - pa) < 0) std::swap(a, b);
      segments.push_back({a, b, f});
    }
  }
  return segments;
}

}  // namespace

const std::array<glm::ivec3, 8>& corners() {
  static const std::array<glm::ivec3, 8> c{
      {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}};
  return c;
}

const std::array<std::array<int, 2>, 12>& edges() {
  static const std::array<std::array<int, 2>, 12> e{
      {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6}, {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}}};
  return e;
}

const std::array<std::array<int, 4>, 6>& faces() {
  static const std::array<std::array<int, 4>, 6> f{
      {{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4}, {3, 2, 6, 7}, {0, 3, 7, 4}, {1, 2, 6, 5}}};
  return f;
}

int ambiguous_faces(int cube_case) {
  int mask = 0;
  for (int f = 0; f < 6; ++f) {
    const auto& q = faces()[size_t(f)];
    const bool a = inside(cube_case, q[0]), b = inside(cube_case, q[1]), c = inside(cube_case, q[2]),
               d = inside(cube_case, q[3]);
    if (a == c && b == d && a != b) mask |= 1 << f;
  }
  return mask;
}

CaseTriangles triangulate_case(int cube_case, int join, bool split_shared_faces) {
  if (cube_case < 0 || cube_case > 255) throw InvalidInput(fmt::format("marching-cubes case {} is not in [0, 255]", cube_case));
  const auto segments = face_segments(cube_case, join);
  std::array<int, 12> next{}, face_of{};
  next.fill(-1);
  for (const auto& [a, b, f] : segments) {
    TESSERA_CHECK_EQ(next[size_t(a)], -1);
    next[size_t(a)] = b;
    face_of[size_t(a)] = f;
  }
  CaseTriangles out;
  std::array<bool, 12> used{};
  for (int start = 0; start < 12; ++start) {  // lowest edge first: each polygon starts at its lowest-numbered edge
    if (next[size_t(start)] < 0 || used[size_t(start)]) continue;
    std::vector<int> polygon;
    std::vector<int> polygon_faces;
    for (int e = start; !used[size_t(e)]; e = next[size_t(e)]) {
      used[size_t(e)] = true;
      polygon.push_back(e);
      polygon_faces.push_back(face_of[size_t(e)]);
    }

    std::vector<int> sorted_faces = polygon_faces;
    std::sort(sorted_faces.begin(), sorted_faces.end());
    const bool shares_face = std::adjacent_find(sorted_faces.begin(), sorted_faces.end()) != sorted_faces.end();
    const size_t n = polygon.size();
    if (split_shared_faces && shares_face) {
      uint16_t mask = 0;
      for (int e : polygon) mask = uint16_t(mask | (1u << e));
      const auto center = uint8_t(kCenter + int(out.center_edges.size()));
      out.center_edges.push_back(mask);
      TESSERA_CHECK_LE(out.center_edges.size(), size_t(kMaxCenters));
      for (size_t i = 0; i < n; ++i) out.triangles.push_back({uint8_t(polygon[i]), uint8_t(polygon[(i + 1) % n]), center});
    } else {
      for (size_t i = 1; i + 1 < n; ++i)
        out.triangles.push_back({uint8_t(polygon[0]), uint8_t(polygon[i]), uint8_t(polygon[i + 1])});
    }
  }
  return out;
}

const std::array<CaseTriangles, 256>& classic_table() {
  static const std::array<CaseTriangles, 256> table = [] {
    std::array<CaseTriangles, 256> t;
    for (int c = 0; c < 256; ++c) t[size_t(c)] = triangulate_case(c, 0, false);
    return t;
  }();
  return table;
}

const std::array<int, 15>& base_cases() {
  // Lorensen & Cline's cases 0-14 as corner sets (Bourke numbering).
  static const std::array<int, 15> cases{0x00, 0x01, 0x03, 0x05, 0x41, 0x32, 0x43, 0x4A,
                                         0x33, 0xB1, 0x69, 0x71, 0x3A, 0xA5, 0xB2};
  return cases;
}

}  // namespace tessera::mc
