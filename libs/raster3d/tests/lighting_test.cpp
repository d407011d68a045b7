// The shading equation against values worked by hand from the notes' and OpenGL's formulas.
#include "tessera/raster3d/lighting.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace tessera::raster3d {
namespace {

void expect_color(const Vec3f& got, const Vec3f& expected, float tolerance = 1e-5f) {
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(got[k], expected[k], tolerance) << "channel " << k;
}

const Vec3f kUp(0, 0, 1);      // a normal facing the viewer
const Vec3f kPoint(0, 0, -3);  // some eye-space point
const Vec3f kWhite(1, 1, 1);

TEST(Lighting, OpenGlDefaults) {
  // Default material (ambient 0.2, diffuse 0.8), light 0 head-on: 0.2 * 0.2 (model ambient) + 0.8 * 1.
  const Lighting lighting;
  expect_color(shade(lighting, kUp, kPoint, kWhite), Vec3f(0.84f));
}

TEST(Lighting, BlinnAndPhongHighlights) {
  // L = (0, 1, 1)/sqrt 2: N.L = cos 45; Blinn H.N = cos 22.5 deg; Phong R = (0, -1, 1)/sqrt 2, E.R = cos 45.
  Lighting lighting;
  lighting.lights[0].position = Vec4f(0, 1, 1, 0);
  lighting.material = Material::plastic(Vec3f(0.2f, 0.1f, 0.0f), 4.0f);
  const float n_dot_l = std::sqrt(0.5f);
  const float blinn = std::pow(std::cos(float(kPi) / 8), 4.0f);
  const float phong = std::pow(std::sqrt(0.5f), 4.0f);
  const Vec3f base = lighting.material.diffuse * (0.2f + n_dot_l);  // C_r (C_a + C_L N.L)
  expect_color(shade(lighting, kUp, kPoint, kWhite), base + Vec3f(blinn));
  lighting.specular_model = SpecularModel::phong;
  expect_color(shade(lighting, kUp, kPoint, kWhite), base + Vec3f(phong));
}

TEST(Lighting, PlasticHighlightsAreWhiteMetalHighlightsTakeTheSurfaceColor) {
  Lighting lighting;
  lighting.lights[0].position = Vec4f(0, 1, 1, 0);
  const float blinn = std::pow(std::cos(float(kPi) / 8), 4.0f);
  lighting.material = Material::plastic(Vec3f(0.5f, 0, 0), 4.0f);
  const Vec3f plastic = shade(lighting, kUp, kPoint, kWhite);
  lighting.material = Material::metal(Vec3f(0.5f, 0, 0), 4.0f);
  const Vec3f metal = shade(lighting, kUp, kPoint, kWhite);
  EXPECT_NEAR(plastic.y, blinn, 1e-5f);  // white highlight lifts green and blue
  EXPECT_NEAR(plastic.z, blinn, 1e-5f);
  EXPECT_EQ(metal.y, 0.0f);  // a red metal's highlight is red
  EXPECT_EQ(metal.z, 0.0f);
  EXPECT_NEAR(metal.x, 0.5f * (0.2f + std::sqrt(0.5f)) + 0.5f * blinn, 1e-5f);
}

TEST(Lighting, BackLitSurfacesGetOnlyAmbient) {
  Lighting lighting;
  lighting.lights[0].position = Vec4f(0, 0, -1, 0);
  lighting.lights[0].ambient = Vec3f(0.1f);
  lighting.material.specular = kWhite;
  lighting.material.shininess = 1;
  expect_color(shade(lighting, kUp, kPoint, kWhite), Vec3f(0.2f * 0.2f + 0.2f * 0.1f));
}

TEST(Lighting, PointLightsAndSeveralLightsAdd) {
  Lighting lighting;
  lighting.material.diffuse = Vec3f(0.5f);
  lighting.material.ambient = Vec3f(0);
  // A point light 4 units above the point, straight along the normal: N.L = 1 (no attenuation, as OpenGL's default).
  lighting.lights[0].position = Vec4f(0, 0, 1, 1);
  lighting.lights[1] = Light{Vec4f(1, 0, 0, 0), Vec3f(0), Vec3f(0, 0, 1), Vec3f(0)};  // grazing: N.L = 0
  lighting.lights[2] = Light{Vec4f(0, 3, 4, 0), Vec3f(0), Vec3f(1, 0, 0), Vec3f(0)};  // N.L = 0.8
  lighting.light_count = 3;
  expect_color(shade(lighting, kUp, kPoint, kWhite), Vec3f(0.5f + 0.4f, 0.5f, 0.5f));
}

TEST(Lighting, EmissionColorMaterialAndClamping) {
  Lighting lighting;
  lighting.material.emission = Vec3f(0.9f, 0, 0);
  lighting.color_material = true;  // the vertex color replaces ambient and diffuse
  const Vec3f c = shade(lighting, kUp, kPoint, Vec3f(0, 0.5f, 0));
  expect_color(c, Vec3f(0.9f, 0.5f * 0.2f + 0.5f, 0));
  lighting.material.emission = Vec3f(3);
  expect_color(shade(lighting, kUp, kPoint, kWhite), Vec3f(1));
}

TEST(Lighting, LocalViewerUsesTheDirectionToTheEye) {
  // A point off to the side: E = normalize(-p) instead of (0, 0, 1) changes the Blinn half vector.
  Lighting lighting;
  lighting.material = Material::plastic(Vec3f(0), 8.0f);
  lighting.local_viewer = true;
  const Vec3f p(3, 0, -3);
  const Vec3f h = glm::normalize(Vec3f(0, 0, 1) + glm::normalize(-p));
  expect_color(shade(lighting, kUp, p, kWhite), Vec3f(std::pow(h.z, 8.0f)));
}

}  // namespace
}  // namespace tessera::raster3d
