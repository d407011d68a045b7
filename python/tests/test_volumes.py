"""Volumes: marching cubes against scikit-image, marching squares against the analytic circle, DVR sanity."""
import numpy as np
import pytest

import tessera


def sphere_field(n=40, radius=0.6):
    axis = np.linspace(-1, 1, n)
    z, y, x = np.meshgrid(axis, axis, axis, indexing="ij")
    return (radius - np.sqrt(x**2 + y**2 + (z * 0.8) ** 2)).astype(np.float32)


def test_marching_cubes_matches_scikit_image():
    measure = pytest.importorskip("skimage.measure")
    field = sphere_field()
    spacing = (0.5, 0.25, 2.0)  # (x, y, z), Tessera's order
    ours = tessera.marching_cubes(tessera.Volume(field, spacing=spacing, origin=(1, 2, 3)), 0.0)
    verts, faces, _, _ = measure.marching_cubes(field, 0.0, spacing=spacing[::-1])
    theirs = verts[:, ::-1] + np.array([1, 2, 3])  # (z, y, x) -> (x, y, z)
    assert ours.vertex_count == len(theirs) and ours.face_count == len(faces)
    # The same edge crossings: sorted vertex sets agree.
    key = lambda v: v[np.lexsort(np.round(v, 4).T[::-1])]
    assert np.abs(key(ours.vertices) - key(theirs)).max() < 1e-4
    area = measure.mesh_surface_area(theirs, faces)
    assert tessera.surface_area(ours) == pytest.approx(area, rel=1e-6)
    assert tessera.topology(ours)["closed"] and tessera.signed_volume(ours) > 0


def test_marching_cubes_takes_plain_arrays_and_keeps_inputs():
    field = sphere_field(24)
    before = field.copy()
    mesh = tessera.marching_cubes(field, 0.1, topological=True)
    assert np.array_equal(field, before)
    assert mesh.normals is not None and mesh.normals.shape == mesh.vertices.shape
    assert mesh.vertices.min() >= 0 and mesh.vertices.max() <= 23
    with pytest.raises(ValueError, match=r"\(Z, Y, X\)"):
        tessera.marching_cubes(np.zeros((4, 4)), 0.0)


def test_marching_squares_traces_a_circle():
    axis = np.arange(64, dtype=np.float32)
    y, x = np.meshgrid(axis, axis, indexing="ij")
    field = np.hypot(x - 31.5, y - 30.0) - 20.0
    lines = tessera.marching_squares(field, 0.0)
    assert len(lines) == 1
    points, closed = lines[0]
    assert closed and points.shape[1] == 2
    radii = np.hypot(points[:, 0] - 31.5, points[:, 1] - 30.0)
    assert np.abs(radii - 20).max() < 0.05


def test_volume_files_and_rendering(tmp_path):
    sphere = tessera.procedural_volume("sphere:32")
    assert sphere.data.shape == (32, 32, 32) and sphere.dims == (32, 32, 32)
    tessera.write_volume(tmp_path / "s.nrrd", sphere)
    back = tessera.read_volume(str(tmp_path / "s.nrrd"))
    assert np.array_equal(back.data, sphere.data) and back.spacing == sphere.spacing
    image = tessera.render_volume(sphere, size=(48, 40))
    assert image.shape == (40, 48, 3)
    assert image[20, 24].max() > 0.05 and image[0, 0].max() == 0  # the object in the middle, background around
    mip = tessera.render_volume(sphere, size=(32, 32), mip=True, view="front")
    assert mip[16, 16, 0] == pytest.approx(mip.max()) and np.allclose(mip[..., 0], mip[..., 1])
    with pytest.raises(tessera.InvalidInput, match="render_volume: unknown option|transfer"):
        tessera.render_volume(sphere, transfer=[[0, 1, 1, 1]])


def test_real_volume_reads_with_its_header(shared_data):
    path = shared_data / "volumes" / "headsq_64x64x93_int16le.mhd"
    if not path.exists():
        pytest.skip(f"no {path}")
    head = tessera.read_volume(path)
    assert head.data.shape == (93, 64, 64)
    raw = np.fromfile(path.with_suffix(".raw"), dtype="<i2").reshape(93, 64, 64)
    assert np.array_equal(head.data, raw.astype(np.float32))


def test_marching_cubes_matches_vtk():
    pytest.importorskip("vtkmodules.vtkFiltersCore")
    from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
    from vtkmodules.vtkCommonDataModel import vtkImageData
    from vtkmodules.vtkFiltersCore import vtkMarchingCubes

    field = sphere_field(36, 0.55)
    spacing, origin = (0.5, 0.75, 1.25), (-2.0, 1.0, 0.5)
    image = vtkImageData()
    image.SetDimensions(field.shape[2], field.shape[1], field.shape[0])  # x, y, z; x varies fastest, as (Z, Y, X)
    image.SetSpacing(*spacing)
    image.SetOrigin(*origin)
    image.GetPointData().SetScalars(numpy_to_vtk(field.ravel(), deep=True))
    mc = vtkMarchingCubes()
    mc.SetInputData(image)
    mc.SetValue(0, 0.0)
    mc.ComputeNormalsOff()
    mc.Update()
    theirs = vtk_to_numpy(mc.GetOutput().GetPoints().GetData()).astype(np.float64)
    ours = tessera.marching_cubes(tessera.Volume(field, spacing, origin), 0.0)
    assert ours.vertex_count == len(theirs) and ours.face_count == mc.GetOutput().GetNumberOfPolys()
    key = lambda v: v[np.lexsort(np.round(v, 4).T[::-1])]
    assert np.abs(key(ours.vertices) - key(theirs)).max() < 1e-4  # VTK's points are float32
