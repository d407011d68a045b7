"""Zero-copy results outlive everything else; 10,000 calls leak neither Python objects nor C++ memory."""
import gc
import resource
import tracemalloc

import numpy as np

import tessera


def rss_kib():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * resource.getpagesize() // 1024


def test_arrays_stay_valid_after_their_owner_is_gone():
    mesh = tessera.subdivide(tessera.cube(), levels=2)
    vertices, faces = mesh.vertices, mesh.face_vertices
    expected = vertices.copy()
    del mesh
    gc.collect()
    tessera.subdivide(tessera.icosahedron(), "loop", 3)  # new allocations that would reuse freed memory
    assert np.array_equal(vertices, expected) and faces.max() < len(vertices)
    image = tessera.render_mesh(tessera.torus(), size=(32, 32))
    rgb = np.asarray(image)[:, :, :3]
    del image
    gc.collect()
    assert rgb.shape == (32, 32, 3) and np.isfinite(rgb).all()
    # Inputs are copied into the core: changing the caller's array afterwards changes nothing.
    field = np.ones((8, 8, 8), np.float32)
    surface = tessera.marching_cubes(field - 0.5, 0.25)
    field[:] = 0
    assert surface.face_count == 0 or np.isfinite(surface.vertices).all()


def test_ten_thousand_calls_do_not_leak():
    points = np.random.default_rng(0).random((64, 3))
    cube = tessera.cube()

    def calls():
        tessera.convert_colors(points, "rgb", "hsv")
        tessera.subdivide(cube, levels=1).vertices.sum()
        tessera.vertex_normals(cube)
        tessera.to_uint8(np.zeros((4, 4, 3), np.float32))
        try:
            tessera.read_mesh("/nonexistent/mesh.obj")
        except tessera.IoError:
            pass

    for _ in range(200):  # warm up: caches, interned strings, the allocator's pools
        calls()
    gc.collect()
    tracemalloc.start()
    before_python, before_rss = tracemalloc.get_traced_memory()[0], rss_kib()
    for _ in range(10_000):
        calls()
    gc.collect()
    after_python, after_rss = tracemalloc.get_traced_memory()[0], rss_kib()
    tracemalloc.stop()
    assert after_python - before_python < 64 * 1024, f"Python objects grew by {after_python - before_python} bytes"
    assert after_rss - before_rss < 4096, f"the resident set grew by {after_rss - before_rss} KiB"
