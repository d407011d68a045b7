#include "tessera/volume/mc_table.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <span>

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

/// The diagonals of the classic table, as "a-b" edge pairs per case: the triangulation of every polygon of four or more
/// vertices that Lorensen & Cline's table (as published by Bourke, and used by vtkMarchingCubes and scikit-image's
/// 'lorensen') chose. No rule of ours (fans from a fixed edge, ear cutting, least area, least diagonal length, one
/// triangulation per symmetry class) reproduces those hand-made choices, so they are written out here; cases without an
/// entry have only triangles. The unit tests check every case against vtkMarchingCubes.
struct ClassicDiagonals {
  int cube_case;
  const char* pairs;
};
constexpr ClassicDiagonals kClassicDiagonals[] = {{3, "1-8"},
                                                  {6, "2-9"},
                                                  {7, "2-8 8-10"},
                                                  {9, "0-11"},
                                                  {11, "1-11 9-11"},
                                                  {12, "3-10"},
                                                  {13, "0-10 8-10"},
                                                  {14, "3-9 9-11"},
                                                  {15, "8-10"},
                                                  {17, "3-4"},
                                                  {19, "1-4 1-7"},
                                                  {21, "3-4"},
                                                  {22, "2-9"},
                                                  {23, "2-7 2-9 7-9"},
                                                  {25, "2-4 4-11"},
                                                  {27, "2-9 4-11 9-11"},
                                                  {28, "3-10"},
                                                  {29, "1-4 1-11 4-11"},
                                                  {30, "0-11 9-11"},
                                                  {31, "4-11 9-11"},
                                                  {34, "0-5"},
                                                  {35, "3-5 5-8"},
                                                  {38, "2-4 2-5"},
                                                  {39, "2-5 3-4 3-5"},
                                                  {41, "0-11"},
                                                  {42, "0-5"},
                                                  {43, "2-5 2-8 5-8"},
                                                  {44, "3-10"},
                                                  {45, "1-8 8-10"},
                                                  {46, "0-5 0-11 5-11"},
                                                  {47, "5-8 8-10"},
                                                  {48, "7-9"},
                                                  {49, "3-5 3-9"},
                                                  {50, "0-7 1-7"},
                                                  {51, "3-5"},
                                                  {52, "7-9"},
                                                  {53, "0-5 3-5"},
                                                  {54, "2-5 2-8 5-8"},
                                                  {55, "2-5 3-5"},
                                                  {56, "7-9"},
                                                  {57, "2-7 2-9 7-9"},
                                                  {58, "1-7 1-8"},
                                                  {59, "1-7 1-11"},
                                                  {60, "5-8 3-10"},
                                                  {61, "0-5 0-7 0-10 0-11"},
                                                  {62, "0-5 0-7 0-10 0-11"},
                                                  {63, "5-11"},
                                                  {67, "1-8"},
                                                  {68, "1-6"},
                                                  {69, "1-6"},
                                                  {70, "0-6 6-9"},
                                                  {71, "2-5 2-8 5-8"},
                                                  {73, "0-11"},
                                                  {75, "2-9 9-11"},
                                                  {76, "3-5 3-6"},
                                                  {77, "0-5 0-11 5-11"},
                                                  {78, "0-5 0-6 3-6"},
                                                  {79, "6-9 9-11"},
                                                  {81, "3-4"},
                                                  {83, "1-7 7-9"},
                                                  {84, "1-6"},
                                                  {85, "2-5 3-4"},
                                                  {86, "0-5 0-6"},
                                                  {87, "2-9 3-9 6-9 7-9"},
                                                  {89, "2-4 2-7"},
                                                  {91, "2-9 4-11 9-11"},
                                                  {92, "3-5 5-11"},
                                                  {93, "0-11 1-11 4-11 5-11"},
                                                  {94, "0-5 0-6 3-6"},
                                                  {95, "6-9 7-9 9-11"},
                                                  {96, "4-10"},
                                                  {97, "4-10"},
                                                  {98, "0-6 0-10"},
                                                  {99, "1-6 1-8 6-8"},
                                                  {100, "1-4 2-4"},
                                                  {101, "2-4 2-9"},
                                                  {102, "2-4"},
                                                  {103, "2-4 2-8"},
                                                  {104, "4-10"},
                                                  {105, "2-8 4-10"},
                                                  {106, "0-6 1-6"},
                                                  {107, "1-4 1-6 1-8 1-11"},
                                                  {108, "3-6 3-9 6-9"},
                                                  {109, "1-4 1-6 1-8 1-11"},
                                                  {110, "0-6 3-6"},
                                                  {111, "6-8"},
                                                  {112, "7-10 8-10"},
                                                  {113, "0-7 0-10 7-10"},
                                                  {114, "1-7 1-8 7-10"},
                                                  {115, "1-7 7-10"},
                                                  {116, "1-6 1-8 6-8"},
                                                  {117, "2-9 3-9 6-9 7-9"},
                                                  {118, "0-6 0-7"},
                                                  {119, "2-7"},
                                                  {120, "6-8 8-10"},
                                                  {121, "0-7 2-7 7-9 7-10"},
                                                  {122, "1-7 1-8 7-10"},
                                                  {123, "1-6 1-7 1-11"},
                                                  {124, "1-6 3-6 6-8 6-9"},
                                                  {126, "0-6 0-7 0-11"},
                                                  {131, "1-8"},
                                                  {134, "2-9"},
                                                  {135, "3-10 8-10"},
                                                  {136, "2-7"},
                                                  {137, "0-6 0-7"},
                                                  {138, "2-7"},
                                                  {139, "1-6 1-8 6-8"},
                                                  {140, "1-7 7-10"},
                                                  {141, "1-7 1-8 7-10"},
                                                  {142, "0-7 0-10 7-10"},
                                                  {143, "7-10 8-10"},
                                                  {144, "6-8"},
                                                  {145, "0-6 3-6"},
                                                  {146, "6-8"},
                                                  {147, "3-6 3-9 6-9"},
                                                  {148, "6-8"},
                                                  {149, "0-6 0-11"},
                                                  {150, "4-11 2-9"},
                                                  {151, "3-4 3-6 3-9 3-10"},
                                                  {152, "2-4 2-8"},
                                                  {153, "2-4"},
                                                  {154, "2-4 3-4"},
                                                  {155, "1-4 2-4"},
                                                  {156, "1-6 1-8 6-8"},
                                                  {157, "0-6 0-10"},
                                                  {158, "3-4 3-6 3-9 3-10"},
                                                  {159, "4-10"},
                                                  {162, "0-5"},
                                                  {163, "3-4 3-5"},
                                                  {166, "2-4 4-10"},
                                                  {167, "2-5 3-4 3-5"},
                                                  {168, "2-7"},
                                                  {169, "0-6 6-8"},
                                                  {170, "3-6 0-5"},
                                                  {171, "1-8 2-8 5-8 6-8"},
                                                  {172, "1-6 1-7"},
                                                  {173, "0-7 1-6 1-7"},
                                                  {174, "0-10 3-10 4-10 7-10"},
                                                  {175, "4-10 7-10 8-10"},
                                                  {176, "6-9 9-11"},
                                                  {177, "0-5 0-6 3-6"},
                                                  {178, "0-5 0-11 5-11"},
                                                  {179, "3-5 3-6"},
                                                  {180, "5-11 9-11"},
                                                  {181, "0-6 0-11 6-9"},
                                                  {182, "0-5 2-5 5-8 5-11"},
                                                  {183, "3-5 3-6 3-10"},
                                                  {184, "2-5 2-8 5-8"},
                                                  {185, "0-6 6-9"},
                                                  {186, "1-8 2-8 5-8 6-8"},
                                                  {187, "1-6"},
                                                  {188, "1-6 3-6 6-8 6-9"},
                                                  {189, "0-5 0-6 0-10"},
                                                  {192, "5-11"},
                                                  {193, "5-11"},
                                                  {194, "5-11"},
                                                  {195, "7-10 1-8"},
                                                  {196, "1-7 1-11"},
                                                  {197, "1-7 2-7"},
                                                  {198, "2-7 2-9 7-9"},
                                                  {199, "2-5 2-7 2-8 2-9"},
                                                  {200, "2-5 3-5"},
                                                  {201, "2-5 2-8 5-8"},
                                                  {202, "3-5 3-10"},
                                                  {203, "2-5 2-7 2-8 2-9"},
                                                  {204, "3-5"},
                                                  {205, "0-7 1-7"},
                                                  {206, "3-5 3-9"},
                                                  {207, "7-9"},
                                                  {208, "5-8 8-10"},
                                                  {209, "0-5 0-11 5-11"},
                                                  {210, "4-10 8-10"},
                                                  {211, "1-4 3-4 4-10 4-11"},
                                                  {212, "2-5 2-8 5-8"},
                                                  {213, "0-11 1-11 4-11 5-11"},
                                                  {214, "0-5 2-5 5-8 5-11"},
                                                  {216, "2-5 3-4 3-5"},
                                                  {217, "2-4 2-5"},
                                                  {218, "3-5 3-10 5-8"},
                                                  {219, "2-4 2-5 2-9"},
                                                  {220, "3-5 5-8"},
                                                  {221, "0-5"},
                                                  {222, "0-5 3-5 5-8"},
                                                  {224, "4-11 9-11"},
                                                  {225, "7-9 9-11"},
                                                  {226, "1-4 1-11 4-11"},
                                                  {227, "1-4 3-4 4-10 4-11"},
                                                  {228, "2-9 4-11 9-11"},
                                                  {229, "1-11 7-9 9-11"},
                                                  {230, "2-4 4-11"},
                                                  {231, "2-4 3-4 4-11"},
                                                  {232, "2-7 2-9 7-9"},
                                                  {233, "0-7 2-7 7-9 7-10"},
                                                  {234, "0-10 3-10 4-10 7-10"},
                                                  {236, "1-4 1-7"},
                                                  {237, "1-4 1-7 1-8"},
                                                  {238, "3-4"},
                                                  {240, "8-10"},
                                                  {241, "3-9 9-11"},
                                                  {242, "0-10 8-10"},
                                                  {243, "3-10"},
                                                  {244, "1-11 9-11"},
                                                  {245, "2-9 3-9 9-11"},
                                                  {246, "0-11"},
                                                  {248, "2-8 8-10"},
                                                  {249, "2-9"},
                                                  {250, "1-8 2-8 8-10"},
                                                  {252, "1-8"}};

std::vector<std::array<int, 2>> classic_diagonals(int cube_case) {
  std::vector<std::array<int, 2>> out;
  for (const auto& [c, pairs] : kClassicDiagonals) {
    if (c != cube_case) continue;
    for (const char* s = pairs; *s;) {
      char* end = nullptr;
      const int a = int(std::strtol(s, &end, 10));
      const int b = int(std::strtol(end + 1, &end, 10));
      out.push_back({a, b});
      s = *end ? end + 1 : end;
    }
  }
  return out;
}

/// Appends the triangles of `polygon` (edge indices in cyclic order), split along those of `diagonals` that join two
/// of its non-adjacent vertices, else fanned from its first vertex. Triangles keep the polygon's orientation.
void triangulate_polygon(const std::vector<int>& polygon, std::span<const std::array<int, 2>> diagonals,
                         std::vector<std::array<uint8_t, 3>>& out) {
  const size_t n = polygon.size();
  for (const auto& [a, b] : diagonals) {
    const auto ia = std::find(polygon.begin(), polygon.end(), a), ib = std::find(polygon.begin(), polygon.end(), b);
    if (ia == polygon.end() || ib == polygon.end()) continue;
    const size_t i = size_t(std::min(ia, ib) - polygon.begin()), j = size_t(std::max(ia, ib) - polygon.begin());
    if (j - i < 2 || j - i > n - 2) continue;  // a side, not a diagonal
    std::vector<int> first(polygon.begin() + std::ptrdiff_t(i), polygon.begin() + std::ptrdiff_t(j) + 1);
    std::vector<int> second(polygon.begin() + std::ptrdiff_t(j), polygon.end());
    second.insert(second.end(), polygon.begin(), polygon.begin() + std::ptrdiff_t(i) + 1);
    triangulate_polygon(first, diagonals, out);
    triangulate_polygon(second, diagonals, out);
    return;
  }
  for (size_t i = 1; i + 1 < n; ++i) out.push_back({uint8_t(polygon[0]), uint8_t(polygon[i]), uint8_t(polygon[i + 1])});
}

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
          pairs.push_back(
              {edge_between(q[size_t((i + 3) % 4)], q[size_t(i)]), edge_between(q[size_t(i)], q[size_t((i + 1) % 4)])});
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

CaseTriangles triangulate_case(int cube_case, int join, bool split_shared_faces,
                               std::span<const std::array<int, 2>> diagonals) {
  if (cube_case < 0 || cube_case > 255)
    throw InvalidInput(fmt::format("marching-cubes case {} is not in [0, 255]", cube_case));
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
      for (size_t i = 0; i < n; ++i)
        out.triangles.push_back({uint8_t(polygon[i]), uint8_t(polygon[(i + 1) % n]), center});
    } else {
      triangulate_polygon(polygon, diagonals, out.triangles);
    }
  }
  return out;
}

const std::array<CaseTriangles, 256>& classic_table() {
  static const std::array<CaseTriangles, 256> table = [] {
    std::array<CaseTriangles, 256> t;
    for (int c = 0; c < 256; ++c) t[size_t(c)] = triangulate_case(c, 0, false, classic_diagonals(c));
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
