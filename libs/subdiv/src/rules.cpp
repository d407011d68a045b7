#include "tessera/subdiv/rules.hpp"

#include <algorithm>
#include <cmath>

#include "tessera/math/types.hpp"

namespace tessera {

void TangentMasks::reset(uint32_t edges, uint32_t faces) {
  for (int t = 0; t < 2; ++t) {
    vertex[t] = 0.0;
    ring[t].assign(edges, 0.0);
    face[t].assign(faces, 0.0);
  }
}

// ---------------------------------------------------------------------------------------------------------------
// Sharpness

float decrement_sharpness(float s) {
  if (s <= 0.0f) return 0.0f;
  if (s >= kInfiniteSharpness) return kInfiniteSharpness;
  return s > 1.0f ? s - 1.0f : 0.0f;
}

float child_edge_sharpness(CreaseMethod method, float s, std::span<const float> around) {
  if (method == CreaseMethod::uniform || around.size() < 2 || s <= 0.0f || s >= kInfiniteSharpness)
    return decrement_sharpness(s);
  // Chaikin: 3/4 of the edge's own sharpness + 1/4 of the mean of the other semi-sharp edges at the vertex.
  float sum = 0.0f;
  int count = 0;
  for (float a : around)
    if (a > 0.0f && a < kInfiniteSharpness) {
      sum += a;
      ++count;
    }
  if (count > 1) s = 0.75f * s + 0.25f * ((sum - s) / float(count - 1));
  s -= 1.0f;
  return s > 0.0f ? s : 0.0f;
}

VertexRule vertex_rule(float vertex_sharpness, int sharp_edges) {
  if (vertex_sharpness > 0.0f || sharp_edges > 2) return VertexRule::corner;
  return sharp_edges == 2 ? VertexRule::crease : sharp_edges == 1 ? VertexRule::dart : VertexRule::smooth;
}

float transition_weight(CreaseMethod method, float parent_vertex, float child_vertex,
                        std::span<const float> parent_edges, std::span<const float> child_edges) {
  int count = 0;
  float sum = 0.0f;
  if (parent_vertex > 0.0f && child_vertex <= 0.0f) {
    count = 1;
    sum = parent_vertex;
  }
  for (size_t i = 0; i < parent_edges.size(); ++i) {
    const float p = parent_edges[i];
    const bool decays = method == CreaseMethod::uniform ? p <= 1.0f : child_edges[i] <= 0.0f;
    if (p > 0.0f && decays) {
      sum += p;
      ++count;
    }
  }
  return count == 0 ? 0.0f : std::min(1.0f, sum / float(count));
}

VertexMask crease_vertex_mask(uint32_t end0, uint32_t end1) {
  return {.vertex = 0.75, .ring = 0.0, .face = 0.0, .crease = 0.125, .crease_ends = {end0, end1}};
}

VertexMask corner_vertex_mask() { return {}; }

VertexMask blend(const VertexMask& parent, const VertexMask& child, double w) {
  VertexMask m;
  m.vertex = w * parent.vertex + (1.0 - w) * child.vertex;
  m.ring = w * parent.ring + (1.0 - w) * child.ring;
  m.face = w * parent.face + (1.0 - w) * child.face;
  const bool parent_crease = parent.crease != 0.0;
  m.crease = parent_crease ? w * parent.crease : (1.0 - w) * child.crease;
  const VertexMask& ends = parent_crease ? parent : child;
  m.crease_ends[0] = ends.crease_ends[0];
  m.crease_ends[1] = ends.crease_ends[1];
  return m;
}

VertexMask crease_limit_mask(uint32_t end0, uint32_t end1) {
  return {.vertex = 2.0 / 3.0, .ring = 0.0, .face = 0.0, .crease = 1.0 / 6.0, .crease_ends = {end0, end1}};
}

// ---------------------------------------------------------------------------------------------------------------
// Catmull-Clark

EdgeMask CatmarkRules::smooth_edge(uint32_t faces, uint32_t size0, uint32_t size1) const {
  if (triangles == TriangleSubdivision::smooth && faces == 2 && (size0 == 3 || size1 == 3)) {
    // OpenSubdiv's TRI_SUB_SMOOTH (after Hbr): triangles pull the edge point toward their face points.
    constexpr double kTriangleWeight = 0.470;
    const double f = 0.5 * ((size0 == 3 ? kTriangleWeight : 0.25) + (size1 == 3 ? kTriangleWeight : 0.25));
    return {.end = 0.5 * (1.0 - 2.0 * f), .face = f};
  }
  return {.end = 0.25, .face = faces == 2 ? 0.25 : 0.5 / double(faces)};
}

VertexMask CatmarkRules::smooth_vertex(uint32_t k) {
  const double w = 1.0 / (double(k) * double(k));
  return {.vertex = double(k - 2) / double(k), .ring = w, .face = w};
}

VertexMask CatmarkRules::smooth_limit(uint32_t k) {
  if (k == 2) return corner_vertex_mask();
  const double f = 1.0 / (double(k) * (double(k) + 5.0));
  return {.vertex = 1.0 - double(k) * 5.0 * f, .ring = 4.0 * f, .face = f};
}

void CatmarkRules::smooth_limit_tangents(uint32_t k, TangentMasks& m) {
  if (k == 2) return corner_limit_tangents(2, 2, m);
  m.reset(k, k);
  const double theta = 2.0 * kPi / double(k);
  const double lambda =
      5.0 / 16.0 + (std::cos(theta) + std::cos(0.5 * theta) * std::sqrt(2.0 * (9.0 + std::cos(theta)))) / 16.0;
  const double face_scale = 1.0 / (4.0 * lambda - 1.0);
  for (uint32_t i = 0; i < k; ++i) {
    const double ci = std::cos(i * theta), cn = std::cos((i + 1) * theta);
    m.ring[0][i] = 4.0 * ci;
    m.face[0][i] = face_scale * (ci + cn);
  }
  // T2 is T1 rotated by one ring position.
  for (uint32_t i = 0; i < k; ++i) {
    m.ring[1][i] = m.ring[0][(i + k - 1) % k];
    m.face[1][i] = m.face[0][(i + k - 1) % k];
  }
}

void CatmarkRules::crease_limit_tangents(uint32_t edges, uint32_t faces, uint32_t e0, uint32_t e1, TangentMasks& m) {
  m.reset(edges, faces);
  // T1 along the crease, toward the leading crease edge.
  m.ring[0][e0] = 0.5;
  m.ring[0][e1] = -0.5;
  // T2 across the faces between the two crease edges (counterclockwise from e0 to e1): Biermann et al. 2000.
  const uint32_t interior = e1 - e0 - 1;
  if (interior == 1) {
    m.vertex[1] = -4.0 / 6.0;
    m.ring[1][e0] = -1.0 / 6.0;
    m.ring[1][e0 + 1] = 4.0 / 6.0;
    m.ring[1][e1] = -1.0 / 6.0;
    m.face[1][e0] = 1.0 / 6.0;
    m.face[1][e0 + 1] = 1.0 / 6.0;
  } else if (interior > 1) {
    const double k = double(interior + 1), theta = kPi / k;
    const double c = std::cos(theta), s = std::sin(theta);
    const double denom = 1.0 / (k * (3.0 + c));
    const double r = (c + 1.0) / s;
    m.vertex[1] = 4.0 * r * (c - 1.0) * denom;
    m.ring[1][e0] = -r * (1.0 + 2.0 * c) * denom;
    m.ring[1][e1] = m.ring[1][e0];
    m.face[1][e0] = s * denom;
    double si = 0.0, si1 = s;
    for (uint32_t i = 1; i < interior + 1; ++i) {
      si = si1;
      si1 = std::sin((i + 1) * theta);
      m.ring[1][e0 + i] = 4.0 * si * denom;
      m.face[1][e0 + i] = (si + si1) * denom;
    }
  } else {
    m.vertex[1] = -6.0;
    m.ring[1][e0] = 3.0;
    m.ring[1][e1] = 3.0;
  }
}

void CatmarkRules::corner_limit_tangents(uint32_t edges, uint32_t faces, TangentMasks& m) {
  m.reset(edges, faces);
  m.vertex[0] = m.vertex[1] = -1.0;
  m.ring[0][0] = 1.0;
  m.ring[1][1] = 1.0;
}

// ---------------------------------------------------------------------------------------------------------------
// Loop

double LoopRules::beta(uint32_t k) const {
  if (weights == LoopWeights::warren) return k > 3 ? 3.0 / (8.0 * double(k)) : 3.0 / 16.0;
  if (k == 6) return 1.0 / 16.0;
  const double b = 0.375 + 0.25 * std::cos(2.0 * kPi / double(k));
  return (0.625 - b * b) / double(k);
}

EdgeMask LoopRules::smooth_edge(uint32_t faces, uint32_t, uint32_t) {
  return {.end = 0.375, .face = faces == 2 ? 0.125 : 0.25 / double(faces)};
}

VertexMask LoopRules::smooth_vertex(uint32_t k) const {
  const double b = beta(k);
  return {.vertex = 1.0 - double(k) * b, .ring = b};
}

VertexMask LoopRules::smooth_limit(uint32_t k) const {
  const double chi = 1.0 / (double(k) + 3.0 / (8.0 * beta(k)));
  return {.vertex = 1.0 - double(k) * chi, .ring = chi};
}

void LoopRules::smooth_limit_tangents(uint32_t k, TangentMasks& m) {
  m.reset(k, k);
  const double alpha = 2.0 * kPi / double(k);
  for (uint32_t i = 0; i < k; ++i) {
    m.ring[0][i] = std::cos(alpha * i);
    m.ring[1][i] = std::sin(alpha * i);
  }
}

void LoopRules::crease_limit_tangents(uint32_t edges, uint32_t faces, uint32_t e0, uint32_t e1, TangentMasks& m) {
  m.reset(edges, faces);
  m.ring[0][e0] = 1.5;
  m.ring[0][e1] = -1.5;
  const uint32_t interior = e1 - e0 - 1;
  if (interior == 2) {
    const double root3 = std::sqrt(3.0);
    m.vertex[1] = -root3;
    m.ring[1][e0] = m.ring[1][e1] = -0.5 * root3;
    m.ring[1][e0 + 1] = m.ring[1][e0 + 2] = root3;
  } else if (interior > 2) {
    const double theta = kPi / double(interior + 1);
    m.ring[1][e0] = m.ring[1][e1] = -3.0 * std::sin(theta);
    const double coeff = -6.0 * (std::cos(theta) - 1.0);
    for (uint32_t i = 1; i <= interior; ++i) m.ring[1][e0 + i] = coeff * std::sin(i * theta);
  } else if (interior == 1) {
    m.vertex[1] = -3.0;
    m.ring[1][e0 + 1] = 3.0;
  } else {
    m.vertex[1] = -6.0;
    m.ring[1][e0] = 3.0;
    m.ring[1][e1] = 3.0;
  }
}

void LoopRules::corner_limit_tangents(uint32_t edges, uint32_t faces, TangentMasks& m) {
  m.reset(edges, faces);
  m.vertex[0] = m.vertex[1] = -3.0;
  m.ring[0][0] = 3.0;
  m.ring[1][1] = 3.0;
}

}  // namespace tessera
