#include "tessera/volume/volume_render.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <optional>

#include "tessera/core/memory_budget.hpp"
#include "tessera/core/parallel.hpp"
#include "tessera/image/metrics.hpp"
#include "tessera/volume/procedural.hpp"
#include "tessera/volume/volume_io.hpp"

namespace tessera {
namespace {

VolumeRenderOptions looking_down_z(int size) {
  VolumeRenderOptions o;
  o.camera.eye = {5, 5, 40};
  o.camera.center = {5, 5, 0};
  o.camera.fovy = radians(10);
  o.width = o.height = size;
  o.shading = false;
  return o;
}

// Issue 24, class 3: the renderer packs every voxel's value and gradient (8 bytes) beside the float volume; that
// copy is checked against the memory budget before it is allocated: 32^3 voxels need 262144 bytes.
TEST(VolumeRender, PackedVolumeOverTheMemoryBudgetIsRefused) {
  const Volume<float> v = make_sphere(32, 0.7);
  MemoryBudget::set_limit(32 * 32 * 32 * 8 - 1);
  std::string message = "no error";
  try {
    VolumeRenderer renderer(v);
  } catch (const MemoryBudgetError& e) {
    message = e.what();
  }
  MemoryBudget::set_limit(32 * 32 * 32 * 8);
  EXPECT_NO_THROW(VolumeRenderer renderer(v));
  MemoryBudget::set_limit(0);
  EXPECT_NE(message.find("volume render: values and gradients of 32x32x32 voxels needs about 256.0 KiB"),
            std::string::npos)
      << message;
}

TEST(VolumeRender, ConstantSlabMatchesBeerLambert) {
  // A 11 x 11 x 11 box of constant value: the central ray crosses 10 units. With opacity a per unit length the
  // compositing result is c (1 - (1 - a)^10) + background (1 - a)^10, for any step.
  Volume<float> v(glm::ivec3(11), 1.0f);
  auto o = looking_down_z(33);
  o.transfer = TransferFunction({{0, {1, 0.5f, 0.25f}, 0.1f}, {2, {1, 0.5f, 0.25f}, 0.1f}});
  o.background = {0, 0, 1};
  o.termination = 1.0f;
  for (float step : {0.5f, 0.3f, 1.0f}) {
    o.step = step;
    const ImageRGB img = render_volume(v, o);
    const float transmittance = std::pow(0.9f, 10.0f);
    const Vec3f center = img(16, 16);
    EXPECT_NEAR(center.x, 1 - transmittance, 1e-3) << step;
    EXPECT_NEAR(center.y, 0.5f * (1 - transmittance), 1e-3) << step;
    EXPECT_NEAR(center.z, 0.25f * (1 - transmittance) + transmittance, 2e-3) << step;
  }
}

TEST(VolumeRender, MaximumIntensityProjectionOfAKnownField) {
  // value = x + y + z: along a ray down -z the maximum is at the front face, z = 10, so the gray is (x+y+10)/30.
  Volume<float> v(glm::ivec3(11));
  for (int z = 0; z < 11; ++z)
    for (int y = 0; y < 11; ++y)
      for (int x = 0; x < 11; ++x) v(x, y, z) = float(x + y + z);
  auto o = looking_down_z(33);
  o.mip = true;
  o.step = 0.25f;
  const ImageRGB img = render_volume(v, o);
  EXPECT_NEAR(img(16, 16).x, 20.0f / 30.0f, 0.01f);
}

TEST(VolumeRender, SameImageForOneAndTwoThreadsAndWithoutSkipping) {
  const auto v = make_metaballs(32);
  VolumeRenderOptions o;
  o.camera.eye = {0.5, 0.8, 3.5};
  o.width = o.height = 48;
  o.transfer = TransferFunction({{0.8f, {1, 0.6f, 0.3f}, 0}, {1.2f, {1, 0.9f, 0.7f}, 0.9f}});
  ImageRGB one, two;
  {
    ThreadLimit limit(1);
    one = render_volume(v, o);
  }
  {
    ThreadLimit limit(2);
    two = render_volume(v, o);
  }
  o.skip_empty = false;
  const ImageRGB plain = render_volume(v, o);
  ASSERT_EQ(one.pixels().size(), two.pixels().size());
  EXPECT_TRUE(std::equal(one.pixels().begin(), one.pixels().end(), two.pixels().begin()));
  EXPECT_TRUE(std::equal(one.pixels().begin(), one.pixels().end(), plain.pixels().begin()));
  // The same for the scalar path (the 8-ray path's jumps over empty blocks are checked above where it runs).
  o.simd = false;
  const ImageRGB scalar_plain = render_volume(v, o);
  o.skip_empty = true;
  const ImageRGB scalar_skipping = render_volume(v, o);
  EXPECT_TRUE(std::equal(scalar_plain.pixels().begin(), scalar_plain.pixels().end(), scalar_skipping.pixels().begin()));
  float sum = 0;
  for (const auto& p : one.pixels()) sum += p.x;
  EXPECT_GT(sum, 1.0f);
}

// The renderer quantizes values and gradients to 16 bits, tabulates the transfer function and the specular power
// and marches 8 rays at a time; this is the notes' algorithm evaluated directly per sample (trilinear value, the
// central-difference gradients of the 8 cell corners interpolated trilinearly, the transfer function with a pow per
// sample), to check that the shortcuts leave the picture essentially unchanged.
ImageRGB direct_render(const Volume<float>& v, const VolumeRenderOptions& o) {
  Camera camera = o.camera;
  camera.aspect = double(o.width) / double(o.height);
  const EyeRays rays(camera, o.width, o.height);
  const float step = o.step > 0 ? o.step : 0.5f * float(v.spacing().x);
  AABB box;
  box.expand(Vec3f(v.origin()));
  box.expand(Vec3f(v.to_world(Vec3(v.dims() - 1))));
  const auto gradient_at = [&](const Vec3f& p) {
    const glm::ivec3 c = glm::min(glm::ivec3(p), v.dims() - 2);
    const Vec3f f = p - Vec3f(c);
    Vec3f g(0.0f);
    for (int corner = 0; corner < 8; ++corner) {
      const glm::ivec3 d(corner & 1, (corner >> 1) & 1, corner >> 2);
      const float w = (d.x ? f.x : 1 - f.x) * (d.y ? f.y : 1 - f.y) * (d.z ? f.z : 1 - f.z);
      g += w * Vec3f(v.gradient(c.x + d.x, c.y + d.y, c.z + d.z));
    }
    return g;
  };
  ImageRGB image(o.width, o.height, o.background);
  for (int j = 0; j < o.height; ++j)
    for (int i = 0; i < o.width; ++i) {
      const Ray ray = rays.ray(i, j);
      float t0 = 0, t1 = 0;
      if (!intersect_slabs(box, ray, 1.0f / ray.dir, t0, t1)) continue;
      Vec3f color(0.0f);
      float alpha = 0;
      for (float a = t0; a < t1 && alpha < o.termination; a += step) {
        const float b = std::min(t1, a + step);
        const Vec3f p = Vec3f(v.to_voxel(Vec3(ray.at(0.5f * (a + b)))));
        const Vec4f c = o.transfer(v.sample(p));
        const float sample_alpha = 1 - std::pow(1 - c.w, b - a);
        const Vec3f g = gradient_at(glm::clamp(p, Vec3f(0.0f), Vec3f(v.dims() - 1)));
        const float cosine = glm::length(g) > 1e-6f ? std::abs(glm::dot(glm::normalize(g), -ray.dir)) : -1.0f;
        const Vec3f rgb = cosine < 0 ? Vec3f(c)
                                     : Vec3f(c) * (o.ambient + o.diffuse * cosine) +
                                           Vec3f(o.specular * std::pow(cosine, o.shininess));
        color += (1 - alpha) * sample_alpha * rgb;
        alpha += (1 - alpha) * sample_alpha;
      }
      image(i, j) = color + (1 - alpha) * o.background;
    }
  return image;
}

VolumeRenderOptions metaball_view() {
  VolumeRenderOptions o;
  o.camera.eye = {0.5, 0.8, 3.5};
  o.width = o.height = 64;
  o.transfer =
      TransferFunction({{0.6f, {1, 0.6f, 0.3f}, 0}, {1.0f, {1, 0.8f, 0.5f}, 0.6f}, {1.4f, {1, 0.95f, 0.8f}, 1.0f}});
  return o;
}

TEST(VolumeRender, MatchesTheDirectPerSampleEvaluation) {
  const auto v = make_metaballs(40);
  const auto o = metaball_view();
  const ImageRGB fast = render_volume(v, o), direct = direct_render(v, o);
  double sum = 0;
  for (const auto& p : direct.pixels()) sum += p.x;
  ASSERT_GT(sum, 50.0);                 // the picture is not empty
  EXPECT_GT(psnr(fast, direct), 50.0);  // 57.7 dB measured
  EXPECT_LT(rmse(fast, direct), 0.003);
}

TEST(VolumeRender, SimdAndScalarPathsAgreeAndAPreparedVolumeRendersTheSame) {
  const auto v = make_metaballs(40);
  auto o = metaball_view();
  const ImageRGB simd = render_volume(v, o);
  o.simd = false;
  const ImageRGB scalar = render_volume(v, o);
  // Up to rounding: FMA and rsqrt in the 8-ray path (where the CPU has AVX2; else both are the scalar path).
  EXPECT_LT(max_abs_difference(simd, scalar), 1e-5);
  const VolumeRenderer renderer(v);
  const ImageRGB again = renderer.render(o), twice = renderer.render(o);
  EXPECT_TRUE(std::equal(scalar.pixels().begin(), scalar.pixels().end(), again.pixels().begin()));
  EXPECT_TRUE(std::equal(again.pixels().begin(), again.pixels().end(), twice.pixels().begin()));
}

TEST(VolumeRender, ThinAndTinyVolumesRenderOnBothPaths) {
  // Axes of one or two voxels: cells clamp to the grid, corner offsets along a single-voxel axis are 0.
  for (const glm::ivec3 dims : {glm::ivec3(16, 16, 1), glm::ivec3(1, 9, 9), glm::ivec3(2, 2, 2), glm::ivec3(1, 1, 1)}) {
    Volume<float> v(dims, 0.0f, Vec3(0.1), Vec3(-0.5));
    for (int z = 0; z < dims.z; ++z)
      for (int y = 0; y < dims.y; ++y)
        for (int x = 0; x < dims.x; ++x) v(x, y, z) = float((x * 7 + y * 3 + z * 5) % 11) / 10.0f;
    auto o = metaball_view();
    o.transfer = TransferFunction({{0.0f, {1, 1, 1}, 0.0f}, {1.0f, {1, 0.5f, 0.2f}, 0.9f}});
    for (const bool simd : {true, false}) {
      o.simd = simd;
      const ImageRGB img = render_volume(v, o);
      for (const auto& p : img.pixels()) ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
    }
  }
}

TEST(TransferFunction, InterpolatesAndParses) {
  const auto tf = TransferFunction::from_csv("# v,r,g,b,a\n0,0,0,0,0\n10,1,1,1,1\n", "t.csv");
  EXPECT_FLOAT_EQ(tf(5).w, 0.5f);
  EXPECT_FLOAT_EQ(tf(20).x, 1.0f);
  EXPECT_FLOAT_EQ(tf.max_opacity(-5, 2), 0.2f);
  const auto j = TransferFunction::from_json(R"({"points": [[0, 1, 0, 0, 0.5]]})", "t.json");
  EXPECT_FLOAT_EQ(j(3).w, 0.5f);
  EXPECT_THROW(TransferFunction::from_csv("1,2\n", "bad.csv"), InvalidInput);
  EXPECT_THROW(TransferFunction::from_json("{", "bad.json"), InvalidInput);
  ValueProfile p;
  p.lo = p.threshold = 0;
  p.hi = p.top = 100;
  p.diagonal = TransferFunction::kReferenceDiagonal;
  EXPECT_THROW(TransferFunction::preset("pet", p), InvalidInput);
  EXPECT_NO_THROW(TransferFunction::preset("ct-bone", p));
}

TEST(TransferFunction, PresetsSitOnTheObjectsScale) {
  // The same preset on 12-bit and 8-bit profiles: the same positions between threshold and top, and opacities per
  // 1/300 of the diagonal, so a volume twice as large gets 1 - (1 - a)^(1/2) per world unit.
  ValueProfile ct;
  ct.lo = 0, ct.hi = 4000, ct.threshold = 640, ct.top = 2533, ct.diagonal = 300;
  ValueProfile foot;
  foot.lo = 0, foot.hi = 255, foot.threshold = 38, foot.top = 255, foot.diagonal = 600;
  const auto a = TransferFunction::preset("ct-bone", ct), b = TransferFunction::preset("ct-bone", foot);
  ASSERT_EQ(a.points().size(), b.points().size());
  for (size_t i = 0; i < a.points().size(); ++i) {
    const double s = (a.points()[i].value - 640.0) / (2533.0 - 640.0);
    EXPECT_NEAR(b.points()[i].value, 38 + s * (255 - 38), 1e-3);
    EXPECT_NEAR(b.points()[i].opacity, 1 - std::sqrt(1 - a.points()[i].opacity), 1e-6);
  }
  // On headsq's profile the bone ramp is where the textbook puts it: from about 1000 to 1150.
  EXPECT_NEAR(a.points()[0].value, 1000, 15);
  EXPECT_NEAR(a.points()[1].value, 1150, 15);
  ValueProfile constant;
  constant.lo = constant.hi = constant.threshold = constant.top = 7;
  try {
    TransferFunction::preset("ct-bone", constant);
    ADD_FAILURE() << "a preset on a constant volume";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("every voxel has the value 7"), std::string::npos) << e.what();
  }
  EXPECT_GT(TransferFunction::automatic(constant)(7).w, 0.0f);  // a constant volume still shows its box
}

TEST(ValueProfile, OtsuThresholdAndTopOfKnownHistograms) {
  // Two values: Otsu's threshold separates them, and the object's top is the upper value.
  Volume<float> two(glm::ivec3(8), 10.0f);
  for (int z = 2; z < 5; ++z)
    for (int y = 2; y < 5; ++y)
      for (int x = 2; x < 5; ++x) two(x, y, z) = 200.0f;
  const ValueProfile p = profile_values(two);
  EXPECT_GT(p.threshold, 10);
  EXPECT_LT(p.threshold, 200);
  EXPECT_DOUBLE_EQ(p.top, 200);
  EXPECT_NEAR(p.diagonal, 7 * std::sqrt(3.0), 1e-9);
  // Values 0..99, 100 voxels each: Otsu's split of a uniform histogram is its middle (between-class variance
  // w0 w1 (m1 - m0)^2 with m1 - m0 = 50 at every split is largest at w0 = w1), and the top is the 99.5th percentile of
  // the upper half, 99.75 of the bin edges.
  Volume<float> ramp(glm::ivec3(100, 10, 10));
  for (int z = 0; z < 10; ++z)
    for (int y = 0; y < 10; ++y)
      for (int x = 0; x < 100; ++x) ramp(x, y, z) = float(x);
  const ValueProfile r = profile_values(ramp);
  EXPECT_NEAR(r.threshold, 49.5, 0.5);
  EXPECT_NEAR(r.top, 99, 1);
  const ValueProfile c = profile_values(Volume<float>(glm::ivec3(3), 5.0f));
  EXPECT_FALSE(c.separable());
}

/// The fraction of pixels brighter than 0.02 (not background black).
double lit_fraction(const ImageRGB& img) {
  size_t lit = 0;
  for (const auto& p : img.pixels()) lit += std::max({p.x, p.y, p.z}) > 0.02f;
  return double(lit) / double(img.pixels().size());
}

/// A three-quarter view (azimuth 30, elevation 20 degrees) framing the volume's bounding sphere, as the CLI's default.
Camera three_quarter(const Volume<float>& v) {
  const Vec3 lo = v.origin(), hi = v.to_world(Vec3(v.dims() - 1)), mid = 0.5 * (lo + hi);
  const double r = 0.5 * glm::length(hi - lo), az = radians(30.0), el = radians(20.0);
  Camera c;
  c.fovy = radians(30.0);
  c.center = mid;
  c.eye = mid + Vec3(std::cos(el) * std::sin(az), std::sin(el), std::cos(el) * std::cos(az)) *
                    (1.1 * r / std::sin(c.fovy / 2));
  return c;
}

/// A volume of the shared data, or nullopt (the caller skips) when they are not there.
std::optional<Volume<float>> shared_volume(const std::string& name) {
  const char* env = std::getenv("TESSERA_SHARED_DATA");
  const auto path = std::filesystem::path(env ? env : TESSERA_SHARED_DATA) / "volumes" / name;
  if (!std::filesystem::exists(path)) return std::nullopt;
  return to_float(read_volume(path.string()));
}

TEST(ValueProfile, SharedVolumesMatchNumpy) {
  // The reference: numpy, the same definitions written independently (np.percentile(a, 99, method="lower"),
  // np.histogram of min(a, p99) in 1024 bins, Otsu's argmax over the bins' upper edges, then np.median and
  // np.percentile(.., 99.5) of the values above the threshold).
  struct Expected {
    const char* file;
    double threshold, median, top;
  };
  for (const Expected& e : {Expected{"foot_256x256x256_uint8.mhd", 32.0117, 51, 255},
                            Expected{"headsq_64x64x93_int16le.mhd", 644.804, 1080, 2529},
                            Expected{"hydrogen_atom_128x128x128_uint8.mhd", 13.0127, 24, 74},
                            Expected{"mr_head_160x232x160_uint8.mhd", 62.1562, 107, 255}}) {
    const auto v = shared_volume(e.file);
    if (!v) GTEST_SKIP() << "no shared data (TESSERA_SHARED_DATA): " << e.file;
    const ValueProfile p = profile_values(*v);
    EXPECT_NEAR(p.threshold, e.threshold, 1e-3) << e.file;
    // The median and top come from a sample of about a million voxels (all of them for the two smaller volumes).
    EXPECT_NEAR(p.median, e.median, 1) << e.file;
    EXPECT_NEAR(p.top, e.top, 1) << e.file;
  }
}

// The foot CT (8-bit) was black with the CT presets, which were written for 12-bit values; presets now fit the data.
TEST(TransferFunction, PresetsShowTheFootCT) {
  const auto v = shared_volume("foot_256x256x256_uint8.mhd");
  if (!v) GTEST_SKIP() << "no shared data (TESSERA_SHARED_DATA): foot_256x256x256_uint8.mhd";
  const ValueProfile p = profile_values(*v);
  VolumeRenderOptions o;
  o.camera = three_quarter(*v);
  o.width = o.height = 64;
  const VolumeRenderer renderer(*v);
  for (const std::string name : TransferFunction::preset_names()) {
    o.transfer = TransferFunction::preset(name, p);
    EXPECT_GT(lit_fraction(renderer.render(o)), 0.1) << name;
  }
  o.transfer = TransferFunction::automatic(p);
  EXPECT_GT(lit_fraction(renderer.render(o)), 0.1) << "automatic";
}

TEST(TransferFunction, AutomaticShowsEveryProceduralVolume) {
  for (const std::string spec : {"sphere:32", "torus:32", "gyroid:32", "metaballs:32", "noise:32"}) {
    Volume<float> v;
    ASSERT_TRUE(make_procedural(spec, v));
    VolumeRenderOptions o;
    o.camera = three_quarter(v);
    o.width = o.height = 48;
    o.transfer = TransferFunction::automatic(profile_values(v));
    EXPECT_GT(lit_fraction(render_volume(v, o)), 0.04) << spec;  // the metaballs, smallest in their box: 0.06
  }
}

TEST(VolumeRender, ProgressCountsEveryPixelOnce) {
  const auto v = make_sphere(16);
  VolumeRenderOptions o;
  o.width = 37, o.height = 21;  // tiles cut at the edges
  o.transfer = TransferFunction::automatic(profile_values(v));
  for (const bool mip : {false, true}) {
    std::atomic<int64_t> pixels = 0;
    o.mip = mip;
    o.progress = [&](int64_t n) { pixels += n; };
    render_volume(v, o);
    EXPECT_EQ(pixels.load(), 37 * 21) << mip;
  }
}

// An orthographic camera: the sphere's silhouette (radius 0.7) is 0.7 / ortho_height of the image height, at any
// distance; a perspective camera's grows as it comes closer.
TEST(VolumeRender, OrthographicSilhouetteHasTheAnalyticRadius) {
  const auto v = make_sphere(64);
  VolumeRenderOptions o;
  o.width = o.height = 101;
  o.shading = false;
  o.transfer = TransferFunction({{-0.005f, {1, 1, 1}, 0}, {0.005f, {1, 1, 1}, 1}});
  o.camera.orthographic = true;
  o.camera.ortho_height = 2.5;
  const Vec3 dir = glm::normalize(Vec3(1, 2, 3));
  const auto radius_px = [&](double distance) {
    o.camera.eye = dir * distance;
    const ImageRGB img = render_volume(v, o);
    size_t lit = 0;
    for (const auto& p : img.pixels()) lit += p.x > 0.5f;
    return std::sqrt(double(lit) / M_PI);
  };
  const double expected = 0.7 / 2.5 * 101;  // 28.28 pixels
  const double near = radius_px(3), far = radius_px(12);
  EXPECT_NEAR(near, expected, 0.5);
  EXPECT_NEAR(far, expected, 0.5);
  EXPECT_NEAR(near, far, 0.1);
  o.camera.orthographic = false;  // the test tells the projections apart: in perspective, nearer is larger
  o.camera.fovy = radians(40.0);
  EXPECT_GT(radius_px(3), radius_px(6) + 5);
}

// Found by fuzz/transfer_fuzz.cpp: a number beyond float's range was converted anyway (undefined behaviour; an infinite
// color in practice), and points near both ends of float's range made the interpolation NaN.
TEST(TransferFunction, RefusesNumbersBeyondFloatAndInterpolatesExtremePoints) {
  const auto message = [](const auto& load) {
    try {
      load();
    } catch (const InvalidInput& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  EXPECT_EQ(message([] { TransferFunction::from_csv("0,0,0,0,0\n1, 2.6e116, 0, 0, 0.5\n", "t.csv"); }),
            "t.csv:2: 2.6e+116 does not fit a float");
  EXPECT_EQ(message([] { TransferFunction::from_json(R"({"points": [[1e300, 0, 0, 0, 0]]})", "t.json"); }),
            "t.json: 1e+300 does not fit a float");
  EXPECT_EQ(message([] { TransferFunction({{0, {0, -1, 0}, 0}}); }), "color component -1 is outside [0, 1000000]");
  EXPECT_EQ(message([] {
              TransferFunction({{0, {2e6f, 0, 0}, 0}});
            }),
            "color component 2000000 is outside [0, 1000000]");
  EXPECT_EQ(message([] { TransferFunction({{INFINITY, {0, 0, 0}, 0}}); }), "point value inf is not finite");
  const auto tf = TransferFunction::from_json(R"({"points": [[-3e38, 0, 0, 0, 0], [3e38, 1, 1, 1, 1]]})", "t.json");
  EXPECT_FLOAT_EQ(tf(0).w, 0.5f);
  EXPECT_FLOAT_EQ(tf(0).x, 0.5f);
}

// Issue 24, class 2: with a step of 1e-5 the per-step opacity 1 - (1 - a)^step rounded to 0 in float, and the
// volume vanished (a black picture, exit 0). Beer-Lambert holds for any step the renderer accepts.
TEST(VolumeRender, TinyStepsStillMatchBeerLambert) {
  Volume<float> v(glm::ivec3(11), 1.0f);
  auto o = looking_down_z(1);  // the central ray only: it crosses 10 units
  o.transfer = TransferFunction({{0, {1, 0.5f, 0.25f}, 0.1f}, {2, {1, 0.5f, 0.25f}, 0.1f}});
  o.termination = 1.0f;
  const float transmittance = std::pow(0.9f, 10.0f);
  for (float step : {1e-3f, 1e-4f, 2e-5f}) {
    o.step = step;
    EXPECT_NEAR(render_volume(v, o)(0, 0).x, 1 - transmittance, 1e-3) << step;  // float opacity: off by 4e-3 at 2e-5
  }
}

// Issue 24, classes 2 and 6 (fuzzer finding): the packed volume's scales were floats, so a value range below ~2e-34
// made 65535 / (hi - lo) infinite (0 * inf = NaN converted to int: undefined) and a range beyond float's limit (values
// of both signs near 3e38) made hi - lo infinite, the value scale 0 and the volume one value. Quantization is
// affine, so a volume scaled to any range must render as its unit-range original: that original is the reference.
TEST(VolumeRender, TinyAndHugeValueRangesRenderAsTheUnitRange) {
  const glm::ivec3 dims(11);
  const auto pattern = [](int x, int y, int z) { return float((x * 7 + y * 3 + z * 5) % 11) / 10.0f; };
  const auto make = [&](double lo, double span) {
    Volume<float> v(dims, 0.0f, Vec3(0.1), Vec3(-0.5));
    for (int z = 0; z < dims.z; ++z)
      for (int y = 0; y < dims.y; ++y)
        for (int x = 0; x < dims.x; ++x) v(x, y, z) = float(lo + span * pattern(x, y, z));
    return v;
  };
  const auto transfer = [](double lo, double span) {
    return TransferFunction({{float(lo), {1, 1, 1}, 0.0f}, {float(lo + span), {1, 0.5f, 0.2f}, 0.9f}});
  };
  for (const bool mip : {false, true})
    for (const bool simd : {true, false}) {
      auto o = metaball_view();
      o.mip = mip;
      o.simd = simd;
      o.transfer = transfer(0, 1);
      const ImageRGB unit = render_volume(make(0, 1), o);
      ASSERT_GT(max_abs_difference(unit, ImageRGB(o.width, o.height, unit(0, 0))), 0.3);  // not one value
      for (const auto& [lo, span] : {std::pair{0.0, 1e-37}, std::pair{1e-36, 1e-36}, std::pair{-3e38, 6e38}}) {
        o.transfer = transfer(lo, span);
        const ImageRGB scaled = render_volume(make(lo, span), o);
        EXPECT_LT(max_abs_difference(scaled, unit), 2e-3) << lo << " + " << span << " mip " << mip << " simd " << simd;
      }
    }
}

// Issue 24, class 2 (fuzzer finding): where t0 + (n - 1) step rounded to the ray's exit t1, the last segment was
// empty, and an opaque entry's opacity correction 1 - (1 - 1)^0 gave 0 * log(0), a NaN pixel. The fuzzer's camera:
// orthographic, along -x, through a 3x5x2 box of spacing (1/8, 3/8, 5/4), 5x8 pixels; pixel (2, 6) is such a ray.
// The values vary along x only, opaque at the exit face: every ray meeting the box crosses the same values, so the
// pixels it covers agree (an empty last segment adds nothing).
TEST(VolumeRender, AnEmptyLastSegmentAddsNothingEvenWhenOpaque) {
  Volume<float> v(glm::ivec3(3, 5, 2), 0.0f, Vec3(0.125, 0.375, 1.25), Vec3(-1.0));
  for (int z = 0; z < 2; ++z)
    for (int y = 0; y < 5; ++y) v(0, y, z) = 1.0f;
  VolumeRenderOptions o;
  o.width = 5;
  o.height = 8;
  o.shading = false;
  o.termination = 1.0f;
  o.transfer = TransferFunction({{0, {1, 0.5f, 0.25f}, 0.0f}, {1, {1, 0.5f, 0.25f}, 1.0f}});
  const Vec3 lo = v.origin(), hi = v.to_world(Vec3(v.dims() - 1));
  const double diagonal = glm::length(hi - lo);
  o.camera.center = 0.5 * (lo + hi);
  o.camera.eye = o.camera.center + Vec3(2 * diagonal, 0, 0);
  o.camera.orthographic = true;
  o.camera.ortho_height = diagonal;
  for (const bool simd : {true, false}) {
    o.simd = simd;
    const ImageRGB img = render_volume(v, o);
    const Vec3f reference = img(1, 6);
    ASSERT_GT(reference.x, 0.05f);
    for (int i = 0; i < 5; ++i) EXPECT_NEAR(img(i, 6).x, reference.x, 1e-3f) << i << " simd " << simd;  // NaN fails too
  }
}

// Issue 24, classes 1 and 2: a step giving more than kMaxSamplesPerRay samples across the box is refused with the
// limit in the message (it hung with --mip, where t += step stopped advancing, and overflowed the int sample count
// otherwise), and so are negative and non-finite steps.
TEST(VolumeRender, RefusesStepsThatGiveTooManySamples) {
  Volume<float> v(glm::ivec3(11), 1.0f);
  for (bool mip : {false, true}) {
    auto o = looking_down_z(8);
    o.mip = mip;
    for (float step : {1e-9f, -1.0f, NAN, INFINITY}) {
      o.step = step;
      EXPECT_THROW(render_volume(v, o), InvalidInput) << step << " mip " << mip;
    }
    o.step = 1e-9f;
    try {
      render_volume(v, o);
    } catch (const InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find("at most 1048576"), std::string::npos) << e.what();
    }
  }
}

// Issue 24, class 1: the MIP loop advanced t += step, which stalls once the step is below half an ulp of t (an eye
// 1e5 units away, a step of 2e-5: the loop never ended). Sample indices are integers now.
TEST(VolumeRender, MipEndsWhenTheStepIsBelowTheUlpOfTheDistance) {
  Volume<float> v(glm::ivec3(11));
  for (int z = 0; z < 11; ++z)
    for (int y = 0; y < 11; ++y)
      for (int x = 0; x < 11; ++x) v(x, y, z) = float(z);
  auto o = looking_down_z(1);
  o.camera.eye = {5, 5, 1e5};
  o.camera.fovy = radians(1e-4);
  o.mip = true;
  o.step = 2e-5f;
  EXPECT_NEAR(render_volume(v, o)(0, 0).x, 1.0f, 1e-3f);  // the front face, z = 10, is the maximum
}

}  // namespace
}  // namespace tessera

namespace tessera {
namespace {

// Sort-last rendering (docs/farm.md): a volume cut into slabs of z, each rendered as a brick that keeps only its
// samples at the whole volume's positions, composited front to back ("over"), is the whole render. Early ray
// termination off, as each brick applies it to its own opacity; both the 8-ray and the scalar paths; slab order
// from the eye (in front of the volume, behind it, and inside its z range).
TEST(VolumeRender, BrickLayersCompositedFrontToBackAreTheWholeRender) {
  const auto whole = make_metaballs(36);
  for (const Vec3 eye : {Vec3(0.4, 0.7, -2.5), Vec3(0.5, 0.8, 3.5), Vec3(3.5, 0.6, 0.45)}) {
    for (const bool simd : {true, false}) {
      SCOPED_TRACE(::testing::Message() << "eye " << eye.z << (simd ? " simd" : " scalar"));
      auto o = metaball_view();
      o.camera.eye = eye;
      o.camera.center = Vec3(0.5);
      o.termination = 1;
      o.simd = simd;
      const VolumeRenderer renderer(whole);
      const ImageRGB reference = renderer.render(o);
      // render() is the layer over the background.
      const ImageRGBA full_layer = renderer.render_layer(o);
      for (size_t i = 0; i < reference.pixels().size(); ++i) {
        const Vec4f c = full_layer.pixels()[i];
        ASSERT_EQ(Vec3f(c) + (1 - c.w) * o.background, reference.pixels()[i]);
      }
      const auto [lo, hi] = value_range(whole);
      const glm::ivec3 dims = whole.dims();
      const int bounds[] = {0, 9, 20, 35};  // cells [0, 9), [9, 20), [20, 35) of z
      std::vector<ImageRGBA> layers;
      for (int b = 0; b < 3; ++b) {
        VolumeRenderOptions::Brick brick{dims, 0, bounds[b], bounds[b + 1], b == 0, b == 2};
        const int z0 = std::max(0, brick.z_begin - 1), z1 = std::min(dims.z - 1, brick.z_end + 1);
        brick.offset = z0;
        Volume<float> part(glm::ivec3(dims.x, dims.y, z1 - z0 + 1), 0.0f, whole.spacing(),
                           whole.to_world(Vec3(0, 0, z0)));
        std::copy_n(&whole(0, 0, z0), part.voxel_count(), &part(0, 0, 0));
        auto bo = o;
        bo.brick = brick;
        layers.push_back(VolumeRenderer(part, lo, hi).render_layer(bo));
      }
      // Front to back: ascending z when the eye is below the volume's z range, descending above it, and from the
      // eye's slab outwards when it is inside (a ray crosses the slabs on one side of it only).
      const double eye_z = (eye.z - whole.origin().z) / whole.spacing().z;
      std::vector<int> order = eye_z < bounds[1]    ? std::vector{0, 1, 2}
                               : eye_z >= bounds[2] ? std::vector{2, 1, 0}
                                                    : std::vector{1, 2, 0};
      double worst = 0;
      for (size_t i = 0; i < reference.pixels().size(); ++i) {
        Vec4f sum(0.0f);
        for (const int b : order) {
          const Vec4f c = layers[size_t(b)].pixels()[i];
          sum += (1 - sum.w) * c;
        }
        const Vec3f composed = Vec3f(sum) + (1 - sum.w) * o.background;
        const Vec3f d = glm::abs(composed - reference.pixels()[i]);
        worst = std::max({worst, double(d.x), double(d.y), double(d.z)});
      }
      EXPECT_LT(worst, 1e-4);
      EXPECT_GT(max_abs_difference(reference, ImageRGB(o.width, o.height, o.background)), 0.1);  // not empty
    }
  }
}

}  // namespace
}  // namespace tessera
