"""Bezier curves and patches against the Bernstein formula; fractals against their closed forms and the CLI."""
import math

import numpy as np
import pytest

import tessera


def bernstein(points, t):
    points = np.asarray(points, float)
    n = len(points) - 1
    basis = np.array([[math.comb(n, i) * s**i * (1 - s) ** (n - i) for i in range(n + 1)] for s in t])
    return basis @ points


@pytest.mark.parametrize("method", ["de-casteljau", "bernstein", "horner"])
def test_bezier_curves_follow_the_bernstein_sum(method):
    points = np.random.default_rng(5).random((6, 3))
    t = np.linspace(0, 1, 33)
    assert np.abs(tessera.bezier(points, t, method) - bernstein(points, t)).max() < 1e-12
    left, right = tessera.bezier_split(points, 0.3)
    assert np.allclose(tessera.bezier(left, [1.0]), tessera.bezier(points, [0.3]))
    assert np.allclose(tessera.bezier(right, t), tessera.bezier(points, 0.3 + 0.7 * t))
    assert np.allclose(tessera.bezier(tessera.bezier_elevate(points), t), tessera.bezier(points, t))
    h = 1e-6
    numeric = (tessera.bezier(points, [0.4 + h]) - tessera.bezier(points, [0.4 - h])) / (2 * h)
    assert np.allclose(tessera.bezier(tessera.bezier_derivative(points), [0.4]), numeric, atol=1e-6)
    levels = tessera.bezier_levels(points[:, :2], 0.5)
    assert [len(level) for level in levels] == [6, 5, 4, 3, 2, 1]
    line = tessera.bezier_flatten(points[:, :2], 1e-3)
    assert np.allclose(line[0], points[0, :2]) and np.allclose(line[-1], points[-1, :2])
    with pytest.raises(tessera.InvalidInput, match="control points"):
        tessera.bezier(np.zeros((3, 4)), [0.5])


def test_teapot_patches(shared_data, tmp_path):
    path = shared_data / "bezier" / "teapot.bpt"
    if not path.exists():
        pytest.skip(f"no {path}")
    patches = tessera.read_patches(path)
    assert patches.shape == (32, 4, 4, 3)
    assert np.allclose(tessera.patch_points(patches, 0, 0), patches[:, 0, 0])
    assert np.allclose(tessera.patch_points(patches, 1, 1), patches[:, 3, 3])
    mesh = tessera.tessellate_patches(patches, 6)
    assert mesh.vertex_count == 32 * 7 * 7 and mesh.face_count == 32 * 2 * 36
    assert mesh.normals is not None and mesh.uvs is not None
    assert tessera.patch_control_net(patches).face_count == 32 * 9
    tessera.write_patches(tmp_path / "copy.bpt", patches)
    assert np.array_equal(tessera.read_patches(tmp_path / "copy.bpt"), patches)


def test_escape_times_match_direct_iteration(tmp_path, cli):
    size, center, scale, cap = (48, 36), complex(-0.5, 0.1), 3.0, 200
    iterations, _ = tessera.mandelbrot(size, center, scale, iterations=cap, raw=True)
    pixel = scale / size[0]
    agree = 0
    for y in range(size[1]):
        for x in range(size[0]):
            c = center + complex((x + 0.5 - size[0] / 2) * pixel, -(y + 0.5 - size[1] / 2) * pixel)
            z, n = 0j, 0
            while n < cap and abs(z) <= 256:
                z, n = z * z + c, n + 1
            agree += (n if abs(z) > 256 else cap) == iterations[y, x]
    assert agree >= 0.999 * size[0] * size[1]
    cli("fractal", "mandelbrot", "-o", tmp_path / "cli.png", "--size", "48x36", "--center=-0.5,0.1", "--iterations", 200)
    tessera.write_image(tmp_path / "py.png", tessera.mandelbrot(size, center, scale, iterations=cap))
    assert (tmp_path / "py.png").read_bytes() == (tmp_path / "cli.png").read_bytes()
    assert tessera.julia_is_connected(-1 + 0j) and not tessera.julia_is_connected(0.5 + 0.5j)
    assert tessera.julia(-0.8 + 0.156j, (16, 12)).shape == (12, 16, 3)


def test_self_similar_sets_have_their_closed_forms():
    assert len(tessera.cantor_set(5)) == 2**5
    assert np.diff(tessera.cantor_set(5), axis=1).sum() == pytest.approx((2 / 3) ** 5)
    assert len(tessera.sierpinski_triangle(4)) == 3**4
    assert len(tessera.sierpinski_carpet(3)) == 8**3
    koch = tessera.koch_curve(4)
    assert len(koch) == 4**4 + 1
    assert np.linalg.norm(np.diff(koch, axis=0), axis=1).sum() == pytest.approx((4 / 3) ** 4)
    assert len(tessera.hilbert_curve(3)) == 4**3
    heights = tessera.midpoint_displacement(depth=5, seed=3)
    assert len(heights) == 33 and heights[0] == heights[-1] == 0
    field = tessera.diamond_square(depth=4)
    assert field.shape == (17, 17)
    assert tessera.height_map_mesh(field).vertex_count == 17 * 17
    assert tessera.triangle_mountain(depth=3).face_count == 4**3


def test_box_counting_measures_the_carpet():
    n = 3**5
    mask = np.zeros((n, n), np.uint8)
    for x, y, w, h in tessera.sierpinski_carpet(5) * n:
        mask[round(y):round(y + h), round(x):round(x + w)] = 1
    result = tessera.box_counting_dimension(mask, factor=3)
    assert result["dimension"] == pytest.approx(math.log(8) / math.log(3), abs=0.02)
