"""Meshes: topology by Euler's formula, corner tables by their definition, subdivision against the CLI's bytes."""
import gc

import numpy as np
import pytest

import tessera


def test_cube_topology_and_measures():
    cube = tessera.cube()
    assert cube.faces.shape == (6, 4)
    t = tessera.topology(cube)
    assert (t["vertices"], t["edges"], t["faces"]) == (8, 12, 6)
    assert t["euler"] == 2 and t["genus"] == 0 and t["closed"] and t["manifold"]
    edge = np.linalg.norm(cube.vertices[cube.faces[0, 0]] - cube.vertices[cube.faces[0, 1]])
    assert tessera.surface_area(cube) == pytest.approx(6 * edge**2)
    assert tessera.signed_volume(cube) == pytest.approx(edge**3)
    torus = tessera.torus(1.0, 0.3, 24, 12)
    assert tessera.topology(torus)["genus"] == 1


def test_meshes_from_numpy_and_ragged_lists():
    square_and_triangle = tessera.Mesh([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [2, 0, 0]],
                                       [[0, 1, 2, 3], [1, 4, 2]])
    assert square_and_triangle.face_count == 2
    assert list(square_and_triangle.face_offsets) == [0, 4, 7]
    with pytest.raises(ValueError, match="face_vertices"):
        square_and_triangle.faces
    tris = tessera.triangulate(square_and_triangle)
    assert tris.faces.shape == (3, 3)
    normals = tessera.face_normals(tris)
    assert np.allclose(normals, [0, 0, 1])

    class Foreign:  # any object with vertices and faces, as trimesh.Trimesh
        vertices = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], dtype=np.float32)
        faces = np.array([[0, 1, 2]], dtype=np.int64)

    assert tessera.surface_area(Foreign()) == pytest.approx(0.5)


def test_bad_meshes_raise_with_the_argument_named():
    with pytest.raises(tessera.InvalidInput, match=r"face_vertices\[2\] = 9 is not a vertex index"):
        tessera.surface_area(tessera.Mesh(np.zeros((3, 3)), np.array([[0, 1, 9]])))

    class Foreign:
        vertices = np.zeros((3, 3))
        faces = np.array([[0, 1, 9]])

    with pytest.raises(tessera.InvalidInput, match=r"faces\[0, 2\] = 9"):
        tessera.surface_area(Foreign())
    with pytest.raises(tessera.InvalidInput, match=r"vertices: expected an \(N, 3\) array"):
        class Flat:
            vertices = np.zeros((3, 2))
            faces = np.array([[0, 1, 2]])
        tessera.surface_area(Flat())
    with pytest.raises(tessera.InvalidInput, match="not finite"):
        tessera.surface_area(tessera.Mesh([[0, 0, np.nan], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]]))
    with pytest.raises(tessera.InvalidInput, match="scheme: expected one of"):
        tessera.subdivide(tessera.cube(), "butterfly")
    with pytest.raises(tessera.InvalidInput):
        tessera.subdivide(tessera.cube(), "loop")  # Loop needs triangles


def test_corner_table_follows_its_definition():
    mesh = tessera.triangulate(tessera.icosahedron())
    table = tessera.CornerTable(mesh)
    V, O = table.vertices, table.opposites
    assert np.array_equal(V, mesh.face_vertices)
    c = np.arange(table.corner_count)
    nxt = 3 * (c // 3) + (c + 1) % 3
    prv = 3 * (c // 3) + (c + 2) % 3
    assert np.array_equal(O[O], c)  # the opposite's opposite
    # O[c] faces the same edge as c, from the other side: its next and prev are c's prev and next vertices.
    assert np.array_equal(V[nxt[O]], V[prv]) and np.array_equal(V[prv[O]], V[nxt])
    assert table.swing(0) != 0 and table.vertex(table.swing(0)) == table.vertex(0)
    assert tessera.CornerTable.next(2) == 0 and tessera.CornerTable.prev(0) == 2


def test_subdivision_equals_the_cli_byte_for_byte(tmp_path, cli, shared_data):
    source = shared_data / "meshes" / "suzanne" / "suzanne.obj"
    if not source.exists():
        pytest.skip(f"no {source}")
    for scheme, extra in [("catmull-clark", []), ("catmull-clark", ["--limit"])]:
        cli("mesh", "subdivide", source, "-o", tmp_path / "cli.obj", "--scheme", scheme, "--levels", 2, *extra)
        ours = tessera.subdivide(tessera.read_mesh(source), scheme, 2, limit=bool(extra))
        tessera.write_mesh(tmp_path / "py.obj", ours)
        assert (tmp_path / "py.obj").read_bytes() == (tmp_path / "cli.obj").read_bytes()


def test_creases_survive_the_round_trip_and_sharpen():
    cube = tessera.cube()
    edges = [(int(a), int(b), 10.0) for a, b in zip(cube.face(0), np.roll(cube.face(0), -1))]
    sharp = tessera.Mesh(cube.vertices, cube.faces, creases=edges)
    assert sharp.crease_edges.shape == (4, 2)
    smooth, creased = tessera.subdivide(cube, levels=3), tessera.subdivide(sharp, levels=3)
    assert creased.crease_edges is not None and len(creased.crease_edges) == 4 * 8
    # The creased face stays flatter: its corner's limit moves less toward the center.
    assert np.abs(creased.vertices).max() > np.abs(smooth.vertices).max()


def test_results_are_zero_copy_views_that_outlive_their_mesh():
    vertices = tessera.subdivide(tessera.cube(), levels=3).vertices
    gc.collect()
    assert not vertices.flags.owndata and vertices.base is not None
    assert vertices.shape == (386, 3) and np.isfinite(vertices).all()
    image = tessera.render_mesh(tessera.cube(), size=(16, 16))
    assert not image.flags.owndata


def test_io_round_trip_and_errors(tmp_path):
    torus = tessera.torus()
    tessera.write_mesh(tmp_path / "t.obj", torus)
    back = tessera.read_mesh(tmp_path / "t.obj")
    assert back.face_count == torus.face_count and np.allclose(back.vertices, torus.vertices, atol=1e-6)
    assert np.allclose(back.corner_uvs, torus.corner_uvs, atol=1e-6)
    tessera.write_mesh(tmp_path / "t.ply", torus)  # PLY has no corner uvs: the seams' vertices are split
    assert tessera.surface_area(tessera.read_mesh(tmp_path / "t.ply")) == pytest.approx(tessera.surface_area(torus))
    (tmp_path / "bad.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n")
    with pytest.raises(tessera.InvalidInput, match="bad.obj:4"):
        tessera.read_mesh(tmp_path / "bad.obj")
    with pytest.raises(tessera.IoError, match="nothing.obj"):
        tessera.read_mesh(tmp_path / "nothing.obj")
