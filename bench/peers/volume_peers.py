"""Peers of bench/volume_bench.cpp, run as a subprocess of it with /usr/bin/python3 (Debian's python3-vtk9 and
python3-skimage; the python3 on PATH may be a shim without them).

  volume_peers.py mc RAW NX NY NZ ISO PEER THREADS REPEAT
      RAW: float32 little-endian, x fastest. PEER: vtk_flying_edges | vtk_marching_cubes | skimage_lorensen.
  volume_peers.py dvr RAW NX NY NZ WIDTH HEIGHT STEP THREADS REPEAT
      vtkFixedPointVolumeRayCastMapper on an offscreen window, if this VTK build can open one.

Prints one line of key=value pairs: peer, backend, threads, best_ms (best wall time of REPEAT runs), cpu_ms (process
CPU time of that run), tris; or status=unavailable reason=... Exits 77 when a package cannot be imported.
Normals are computed and scalars are not, as Tessera does (normals on, no per-vertex values).
"""
import os
import sys
import time

import numpy as np


def load(path, nx, ny, nz):
    # Memory-mapped then copied once: the timed runs see an ordinary in-memory array, as Tessera does.
    return np.ascontiguousarray(np.fromfile(path, dtype="<f4").reshape(nz, ny, nx))


def vtk_image(field, spacing):
    from vtk.util import numpy_support
    import vtk

    nz, ny, nx = field.shape
    image = vtk.vtkImageData()
    image.SetDimensions(nx, ny, nz)
    image.SetSpacing(spacing, spacing, spacing)
    image.SetOrigin(-1.0, -1.0, -1.0)
    scalars = numpy_support.numpy_to_vtk(field.ravel(), deep=0)  # zero copy; `field` outlives the image
    image.GetPointData().SetScalars(scalars)
    return image


def set_threads(threads):
    import vtk

    vtk.vtkSMPTools.Initialize(threads)
    return vtk.vtkSMPTools.GetBackend(), vtk.vtkSMPTools.GetEstimatedNumberOfThreads()


def best_of(repeat, run):
    best = None
    for _ in range(repeat):
        cpu0, wall0 = time.process_time(), time.perf_counter()
        result = run()
        wall, cpu = time.perf_counter() - wall0, time.process_time() - cpu0
        if best is None or wall < best[0]:
            best = (wall, cpu, result)
    return best


def mc(args):
    path, nx, ny, nz, iso, peer, threads, repeat = args
    nx, ny, nz, iso, threads, repeat = int(nx), int(ny), int(nz), float(iso), int(threads), int(repeat)
    field = load(path, nx, ny, nz)
    backend, used = "none", 1
    if peer.startswith("vtk"):
        try:
            import vtk
        except ImportError:
            sys.exit(77)
        backend, used = set_threads(threads)
        image = vtk_image(field, 2.0 / (nx - 1))

        def run():
            f = vtk.vtkFlyingEdges3D() if peer == "vtk_flying_edges" else vtk.vtkMarchingCubes()
            f.SetInputData(image)
            f.SetValue(0, iso)
            f.ComputeNormalsOn()
            f.ComputeGradientsOff()
            f.ComputeScalarsOff()
            f.Update()
            return f.GetOutput().GetNumberOfPolys()
        if peer == "vtk_marching_cubes":
            used = 1  # vtkMarchingCubes is serial whatever the SMP backend
    elif peer == "skimage_lorensen":
        try:
            from skimage import measure
        except ImportError:
            sys.exit(77)

        def run():
            _, faces, _, _ = measure.marching_cubes(field, iso, method="lorensen")
            return len(faces)
    else:
        sys.exit(f"unknown peer {peer}")
    wall, cpu, tris = best_of(repeat, run)
    print(f"peer={peer} backend={backend} threads={used} best_ms={wall * 1e3:.1f} cpu_ms={cpu * 1e3:.1f} tris={tris}")


def dvr(args):
    path, nx, ny, nz, width, height, step, threads, repeat = args
    nx, ny, nz, width, height, threads, repeat = int(nx), int(ny), int(nz), int(width), int(height), int(threads), int(repeat)
    try:
        import vtk
    except ImportError:
        sys.exit(77)
    window = vtk.vtkRenderWindow()
    # Debian's VTK 9.1 is built for X only (no EGL/OSMesa window class): without a display it cannot render, and
    # trying aborts the process, so say so instead.
    if window.GetClassName() == "vtkXOpenGLRenderWindow" and not os.environ.get("DISPLAY"):
        print("peer=vtk_fixed_point_ray_cast status=unavailable reason=X-only-VTK-build-and-no-DISPLAY")
        return
    backend, used = set_threads(threads)
    field = load(path, nx, ny, nz)
    image = vtk_image(field, 2.0 / (nx - 1))
    # The same transfer function as the benchmark's (noise values; clear below 0).
    color, opacity = vtk.vtkColorTransferFunction(), vtk.vtkPiecewiseFunction()
    for value, r, g, b, a in ((0.0, 0.9, 0.6, 0.4, 0.0), (0.2, 0.9, 0.6, 0.4, 0.5), (0.6, 1.0, 1.0, 0.9, 1.0)):
        color.AddRGBPoint(value, r, g, b)
        # Opacity per world unit, as Tessera's: the mapper itself corrects it to the sample distance,
        # alpha = 1 - (1 - opacity)^(SampleDistance / ScalarOpacityUnitDistance) (vtkFixedPointVolumeRayCastMapper::
        # UpdateColorTable), with the unit distance 1.
        opacity.AddPoint(value, a)
    prop = vtk.vtkVolumeProperty()
    prop.SetColor(color)
    prop.SetScalarOpacity(opacity)
    prop.SetScalarOpacityUnitDistance(1.0)
    prop.SetInterpolationTypeToLinear()
    prop.ShadeOn()
    # Tessera's lighting defaults (ambient + diffuse + Blinn specular; the renderer's default light is a headlight).
    prop.SetAmbient(0.3)
    prop.SetDiffuse(0.7)
    prop.SetSpecular(0.3)
    prop.SetSpecularPower(32.0)
    mapper = vtk.vtkFixedPointVolumeRayCastMapper()
    mapper.SetInputData(image)
    mapper.AutoAdjustSampleDistancesOff()
    mapper.SetSampleDistance(float(step))
    mapper.SetNumberOfThreads(threads)
    volume = vtk.vtkVolume()
    volume.SetMapper(mapper)
    volume.SetProperty(prop)
    renderer = vtk.vtkRenderer()
    renderer.AddVolume(volume)
    camera = renderer.GetActiveCamera()
    camera.SetPosition(2.2, 1.6, 2.8)
    camera.SetFocalPoint(0, 0, 0)
    camera.SetViewUp(0, 1, 0)
    camera.SetViewAngle(40)
    window.SetOffScreenRendering(1)
    window.AddRenderer(renderer)
    window.SetSize(width, height)
    window.Render()  # first render builds the gradient and min/max tables; not timed, as Tessera's are per call

    def run():
        volume.Modified()
        window.Render()
        return 0

    wall, cpu, _ = best_of(repeat, run)
    if os.environ.get("TESSERA_DVR_IMAGE_DIR"):  # for comparing the pictures (the benchmark writes Tessera's there)
        grab = vtk.vtkWindowToImageFilter()
        grab.SetInput(window)
        grab.ReadFrontBufferOff()
        writer = vtk.vtkPNGWriter()
        writer.SetFileName(os.path.join(os.environ["TESSERA_DVR_IMAGE_DIR"], f"dvr_vtk_{threads}.png"))
        writer.SetInputConnection(grab.GetOutputPort())
        writer.Write()
    print(f"peer=vtk_fixed_point_ray_cast backend={backend} threads={used} best_ms={wall * 1e3:.1f} cpu_ms={cpu * 1e3:.1f}")


if __name__ == "__main__":
    {"mc": mc, "dvr": dvr}[sys.argv[1]](sys.argv[2:])
