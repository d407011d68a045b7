#include "tessera/subdiv/rules.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

namespace tessera {
namespace {

double sum(const VertexMask& m, uint32_t edges, uint32_t faces) {
  return m.vertex + edges * m.ring + faces * m.face + 2.0 * m.crease;
}

TEST(Sharpness, UniformDecay) {
  EXPECT_EQ(decrement_sharpness(0.0f), 0.0f);
  EXPECT_EQ(decrement_sharpness(-1.0f), 0.0f);
  EXPECT_EQ(decrement_sharpness(0.5f), 0.0f);
  EXPECT_EQ(decrement_sharpness(1.0f), 0.0f);
  EXPECT_EQ(decrement_sharpness(2.5f), 1.5f);
  EXPECT_EQ(decrement_sharpness(10.0f), 10.0f);
  EXPECT_EQ(decrement_sharpness(25.0f), 10.0f);
}

TEST(Sharpness, Chaikin) {
  const float around[] = {2.0f, 1.0f, 0.0f, 10.0f};
  // 3/4 * 2 + 1/4 * 1 (the other semi-sharp edge; the infinite one does not count) - 1.
  EXPECT_FLOAT_EQ(child_edge_sharpness(CreaseMethod::chaikin, 2.0f, around), 0.75f);
  EXPECT_FLOAT_EQ(child_edge_sharpness(CreaseMethod::chaikin, 1.0f, around), 0.25f);  // 3/4 + 1/4 * 2 - 1
  EXPECT_FLOAT_EQ(child_edge_sharpness(CreaseMethod::chaikin, 10.0f, around), 10.0f);
  EXPECT_FLOAT_EQ(child_edge_sharpness(CreaseMethod::uniform, 2.0f, around), 1.0f);
}

TEST(Sharpness, VertexRules) {
  EXPECT_EQ(vertex_rule(0.0f, 0), VertexRule::smooth);
  EXPECT_EQ(vertex_rule(0.0f, 1), VertexRule::dart);
  EXPECT_EQ(vertex_rule(0.0f, 2), VertexRule::crease);
  EXPECT_EQ(vertex_rule(0.0f, 3), VertexRule::corner);
  EXPECT_EQ(vertex_rule(0.5f, 0), VertexRule::corner);
}

TEST(Sharpness, TransitionWeight) {
  const float parent[] = {0.5f, 0.0f, 0.3f, 0.0f}, child[] = {0.0f, 0.0f, 0.0f, 0.0f};
  EXPECT_FLOAT_EQ(transition_weight(CreaseMethod::uniform, 0.0f, 0.0f, parent, child), 0.4f);
  EXPECT_FLOAT_EQ(transition_weight(CreaseMethod::uniform, 0.9f, 0.0f, {}, {}), 0.9f);
  const float sharp[] = {3.0f, 3.0f}, decayed[] = {2.0f, 2.0f};
  EXPECT_FLOAT_EQ(transition_weight(CreaseMethod::uniform, 0.0f, 0.0f, sharp, decayed), 0.0f);
}

TEST(Masks, AffineInvariance) {
  const CatmarkRules catmark;
  const LoopRules warren{LoopWeights::warren}, loop{LoopWeights::loop};
  for (uint32_t k = 3; k <= 12; ++k) {
    EXPECT_NEAR(sum(CatmarkRules::smooth_vertex(k), k, k), 1.0, 1e-15);
    EXPECT_NEAR(sum(CatmarkRules::smooth_limit(k), k, k), 1.0, 1e-15);
    EXPECT_NEAR(sum(warren.smooth_vertex(k), k, 0), 1.0, 1e-15);
    EXPECT_NEAR(sum(loop.smooth_vertex(k), k, 0), 1.0, 1e-15);
    EXPECT_NEAR(sum(loop.smooth_limit(k), k, 0), 1.0, 1e-15);
    TangentMasks t;
    CatmarkRules::smooth_limit_tangents(k, t);
    for (int i = 0; i < 2; ++i) {
      const double total = t.vertex[i] + std::accumulate(t.ring[i].begin(), t.ring[i].end(), 0.0) +
                           std::accumulate(t.face[i].begin(), t.face[i].end(), 0.0);
      EXPECT_NEAR(total, 0.0, 1e-12);
    }
  }
  const EdgeMask e = catmark.smooth_edge(2, 4, 4);
  EXPECT_DOUBLE_EQ(2 * e.end + 2 * e.face, 1.0);
  const EdgeMask l = LoopRules::smooth_edge(2, 3, 3);
  EXPECT_DOUBLE_EQ(l.end, 0.375);
  EXPECT_DOUBLE_EQ(l.face, 0.125);
  EXPECT_NEAR(sum(crease_vertex_mask(0, 2), 4, 0), 1.0, 1e-15);
  EXPECT_NEAR(sum(crease_limit_mask(0, 2), 4, 0), 1.0, 1e-15);
}

TEST(Masks, LoopBeta) {
  const LoopRules warren{LoopWeights::warren}, loop{LoopWeights::loop};
  EXPECT_DOUBLE_EQ(warren.beta(3), 3.0 / 16.0);
  EXPECT_DOUBLE_EQ(warren.beta(5), 3.0 / 40.0);
  EXPECT_DOUBLE_EQ(warren.beta(6), 1.0 / 16.0);
  EXPECT_DOUBLE_EQ(loop.beta(6), 1.0 / 16.0);
  EXPECT_NEAR(loop.beta(3), 0.1875, 1e-15);  // Loop's original also gives 3/16 at valence 3
  EXPECT_NEAR(loop.beta(5), (0.625 - std::pow(0.375 + 0.25 * std::cos(2 * 3.14159265358979323846 / 5), 2)) / 5, 1e-15);
  EXPECT_GT(std::abs(loop.beta(5) - warren.beta(5)), 1e-3);
}

TEST(Masks, CatmullClarkVertexRuleIsTheTextbookForm) {
  // ((k-2) v + mean(ends) + mean(face points)) / k == (F + 2 R_mid + (k-3) v) / k with R_mid = (v + mean(ends)) / 2.
  for (uint32_t k = 3; k <= 8; ++k) {
    const VertexMask m = CatmarkRules::smooth_vertex(k);
    EXPECT_NEAR(m.vertex, (1.0 + (k - 3.0)) / k, 1e-15);
    EXPECT_NEAR(m.ring * k, 1.0 / k, 1e-15);
    EXPECT_NEAR(m.face * k, 1.0 / k, 1e-15);
  }
}

TEST(Masks, SemiSharpBlend) {
  const VertexMask b = blend(crease_vertex_mask(1, 3), CatmarkRules::smooth_vertex(4), 0.25);
  EXPECT_DOUBLE_EQ(b.vertex, 0.25 * 0.75 + 0.75 * 0.5);
  EXPECT_DOUBLE_EQ(b.crease, 0.25 * 0.125);
  EXPECT_EQ(b.crease_ends[0], 1u);
  EXPECT_EQ(b.crease_ends[1], 3u);
  EXPECT_NEAR(sum(b, 4, 4), 1.0, 1e-15);
}

}  // namespace
}  // namespace tessera
