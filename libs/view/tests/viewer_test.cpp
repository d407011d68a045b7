// The Viewer sketch run headless by the sketch runner: a scripted drag reaches the arcball with the window's rows
// turned upward, a right drag pans, the wheel zooms, keys change the shading and step the subdivision (Catmull-Clark
// for quads, Loop for triangles: face counts of the cube and the tetrahedron by hand), and r goes home.
#include "tessera/view/viewer.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "tessera/mesh/primitives.hpp"
#include "tessera/sketch/runner.hpp"

namespace tessera {
namespace {

Viewable mesh_viewable(PolyMesh mesh) {
  Viewable v;
  v.kind = ViewableKind::mesh;
  v.name = "test.obj";
  v.mesh = std::move(mesh);
  return v;
}

/// Runs a 64 x 48 viewer of `v` with `script` (input.hpp's format) and returns it after the run.
std::unique_ptr<Viewer> run(Viewable v, const std::string& script) {
  ViewerOptions options;
  options.width = 64;
  options.height = 48;
  auto viewer = std::make_unique<Viewer>(std::move(v), options);
  RunOptions run;
  run.events = parse_input_script(script);
  run_sketch(*viewer, run);
  return viewer;
}

TEST(Viewer, ALeftDragTurnsTheArcballFromWindowRows) {
  const auto viewer = run(mesh_viewable(make_cube()),
                          "1 mouse_move 32 24\n1 mouse_press left\n1 mouse_move 44 14\n1 mouse_release left\n");
  // The ball has radius 24 about (32, 24): (44, 14) is (0.5, 10/24) in ball radii, y up.
  const double px = 0.5, py = 10.0 / 24, pz = std::sqrt(1 - px * px - py * py);
  const Quat want = glm::normalize(Quat(pz, -py, px, 0));  // [a . b, a x b] with a = (0, 0, 1), b = (px, py, pz)
  const Quat got = viewer->control().orientation();
  EXPECT_NEAR(std::abs(glm::dot(got, want)), 1.0, 1e-12);
}

TEST(Viewer, ARightDragPansAndTheWheelZooms) {
  const auto home = run(mesh_viewable(make_cube()), "");
  const auto moved = run(mesh_viewable(make_cube()),
                         "1 mouse_move 10 10\n1 mouse_press right\n1 mouse_move 20 10\n1 mouse_release right\n"
                         "1 mouse_wheel 2\n");
  EXPECT_GT(moved->control().pan().x, 0);
  EXPECT_DOUBLE_EQ(moved->control().pan().y, 0);
  EXPECT_NEAR(moved->control().distance(), home->control().distance() * 1.21, 1e-9);
}

TEST(Viewer, KeysChangeTheShadingAndTheSubdivisionLevel) {
  // A cube's 6 quads: Catmull-Clark gives 24, then 96.
  auto viewer = run(mesh_viewable(make_cube()), "1 key_press 2\n2 key_press +\n3 key_press +\n");
  EXPECT_NE(viewer->status().find("96 faces, flat"), std::string::npos) << viewer->status();
  EXPECT_NE(viewer->status().find("Catmull-Clark level 2"), std::string::npos) << viewer->status();
  // A tetrahedron's 4 triangles: Loop gives 16; - goes back to the 4.
  PolyMesh tet;
  tet.positions = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
  tet.add_face({0, 1, 2});
  tet.add_face({0, 3, 1});
  tet.add_face({0, 2, 3});
  tet.add_face({1, 3, 2});
  viewer = run(mesh_viewable(tet), "1 key_press +\n");
  EXPECT_NE(viewer->status().find("16 faces"), std::string::npos) << viewer->status();
  EXPECT_NE(viewer->status().find("Loop level 1"), std::string::npos) << viewer->status();
  viewer = run(mesh_viewable(tet), "1 key_press +\n2 key_press -\n3 key_press 6\n");
  EXPECT_NE(viewer->status().find("4 faces, normals"), std::string::npos) << viewer->status();
}

TEST(Viewer, ResetGoesHome) {
  const auto viewer = run(mesh_viewable(make_cube()),
                          "1 mouse_move 32 24\n1 mouse_press left\n1 mouse_move 50 30\n1 mouse_release left\n"
                          "1 mouse_wheel 3\n2 key_press r\n");
  EXPECT_NEAR(std::abs(viewer->control().orientation().w), 1.0, 1e-15);
  EXPECT_EQ(viewer->control().pan(), Vec2(0.0));
}

}  // namespace
}  // namespace tessera
