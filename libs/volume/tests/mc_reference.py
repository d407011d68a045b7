"""Reference iso-surfaces for the volume tests and benchmark (run with /usr/bin/python3; never used by the library).

  mc_reference.py field RAW NX NY NZ ISO METHOD   float32 little-endian field, x fastest; prints "tris=N area=A seconds=S"
                                                  METHOD: vtk (vtkMarchingCubes), flying_edges (vtkFlyingEdges3D),
                                                  lorensen / lewiner (skimage.measure.marching_cubes)
  mc_reference.py fields LIST                     LIST: lines "NAME RAW NX NY NZ ISO"; prints "NAME METHOD tris=N area=A"
                                                  for vtk, lorensen and lewiner (one interpreter start for all)
  mc_reference.py cases RAW                       256 cubes of 8 float32 corner values (Bourke order), iso 0.5;
                                                  prints "tris area e0 e1 e2 ..." per case from vtkMarchingCubes: the
                                                  triangles as the cube edges (Bourke numbering) their corners lie on
Exits 77 when the needed package cannot be imported.
"""
import sys
import time

import numpy as np


def area_of(points, tris):
    if len(tris) == 0:
        return 0.0
    a, b, c = points[tris[:, 0]], points[tris[:, 1]], points[tris[:, 2]]
    return float(0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1).sum())


CORNERS = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
EDGES = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4), (0, 4), (1, 5), (2, 6), (3, 7)]


def edge_of(point):
    """The unit-cube edge a point lies on: the one whose two coordinates that stay fixed match the point's."""
    for e, (a, b) in enumerate(EDGES):
        pa, pb = np.array(CORNERS[a]), np.array(CORNERS[b])
        fixed = pa == pb
        if np.all(np.abs(point[fixed] - pa[fixed]) < 1e-6):
            return e
    raise ValueError(f"point {point} is on no cube edge")


def vtk_surface(field, iso, flying_edges, with_mesh=False):
    try:
        import vtk
        from vtk.util import numpy_support
    except ImportError:
        sys.exit(77)
    nz, ny, nx = field.shape
    image = vtk.vtkImageData()
    image.SetDimensions(nx, ny, nz)
    image.GetPointData().SetScalars(numpy_support.numpy_to_vtk(field.ravel(), deep=1))
    mc = vtk.vtkFlyingEdges3D() if flying_edges else vtk.vtkMarchingCubes()
    mc.SetInputData(image)
    mc.SetValue(0, iso)
    mc.ComputeNormalsOff()
    mc.ComputeGradientsOff()
    mc.ComputeScalarsOff()
    start = time.perf_counter()
    mc.Update()
    seconds = time.perf_counter() - start
    out = mc.GetOutput()
    points = numpy_support.vtk_to_numpy(out.GetPoints().GetData()).astype(np.float64) if out.GetNumberOfPoints() else np.zeros((0, 3))
    polys = numpy_support.vtk_to_numpy(out.GetPolys().GetData()).reshape(-1, 4)[:, 1:] if out.GetNumberOfCells() else np.zeros((0, 3), int)
    if with_mesh:
        return points, polys
    return len(polys), area_of(points, polys), seconds


def skimage_surface(field, iso, method):
    try:
        from skimage import measure
    except ImportError:
        sys.exit(77)
    start = time.perf_counter()
    verts, faces, _, _ = measure.marching_cubes(field, iso, method=method)
    seconds = time.perf_counter() - start
    return len(faces), area_of(verts.astype(np.float64), faces), seconds


def main():
    if sys.argv[1] == "cases":
        try:
            import vtk  # noqa: F401
        except ImportError:
            sys.exit(77)
        cubes = np.fromfile(sys.argv[2], dtype="<f4").reshape(256, 8)
        for values in cubes:
            field = np.zeros((2, 2, 2), dtype=np.float32)
            for (x, y, z), value in zip(CORNERS, values):
                field[z, y, x] = value
            points, polys = vtk_surface(field, 0.5, False, with_mesh=True)
            edges = [edge_of(points[i]) for tri in polys for i in tri]
            print(len(polys), repr(area_of(points, polys)), *edges)
        return
    if sys.argv[1] == "fields":
        for line in open(sys.argv[2]):
            name, path, nx, ny, nz, iso = line.split()
            field = np.fromfile(path, dtype="<f4").reshape(int(nz), int(ny), int(nx))
            for method in ("vtk", "lorensen", "lewiner"):
                if method == "vtk":
                    tris, area, _ = vtk_surface(field, float(iso), False)
                else:
                    tris, area, _ = skimage_surface(field, float(iso), method)
                print(f"{name} {method} tris={tris} area={area!r}")
        return
    _, _, path, nx, ny, nz, iso, method = sys.argv
    field = np.fromfile(path, dtype="<f4").reshape(int(nz), int(ny), int(nx))
    iso = float(iso)
    if method in ("vtk", "flying_edges"):
        tris, area, seconds = vtk_surface(field, iso, method == "flying_edges")
    else:
        tris, area, seconds = skimage_surface(field, iso, method)
    print(f"tris={tris} area={area!r} seconds={seconds!r}")


if __name__ == "__main__":
    main()
