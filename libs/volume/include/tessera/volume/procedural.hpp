#pragma once
// Procedural volumes for tests, demos and the CLI (`sphere:64`): analytic fields sampled on an n^3 grid.
//
// Every field is "inside" where it is >= its natural iso value (given with each function), so marching cubes and the
// renderers treat them like CT densities. The grid spans [-1, 1]^3 in world units (spacing 2 / (n - 1)).
#include <cstdint>
#include <string>

#include "tessera/volume/volume.hpp"

namespace tessera {

/// r - |p| for a ball of radius r centered at c (world units): the sphere is the iso value 0. n >= 2.
Volume<float> make_sphere(int n, double radius = 0.7, const Vec3& center = Vec3(0.0));
/// R_minor - distance to the circle of radius R_major in the xy plane: the torus is the iso value 0.
Volume<float> make_torus(int n, double major = 0.6, double minor = 0.25);
/// The gyroid sin x cos y + sin y cos z + sin z cos x with `periods` periods across the grid; iso 0.
Volume<float> make_gyroid(int n, double periods = 2);
/// Blinn's metaballs: sum of r_i^2 / |p - c_i|^2 over a few fixed balls; the blob surface is iso 1.
Volume<float> make_metaballs(int n);
/// Smooth value noise in [-1, 1] (trilinear interpolation of seeded random lattice values, 4 octaves); iso 0.
Volume<float> make_noise(int n, uint64_t seed = 1, double frequency = 4);

/// A procedural volume by name: "sphere:N", "torus:N", "gyroid:N", "metaballs:N" or "noise:N[:SEED]".
/// Returns false (and leaves `out` alone) when `spec` does not name one; throws InvalidInput for a bad size.
bool make_procedural(const std::string& spec, Volume<float>& out);

}  // namespace tessera
