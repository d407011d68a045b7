"""Tessera: a C++20 computer-graphics toolkit on numpy arrays (docs/python.md).

Images are float32 arrays (H, W, C) of linear values (the Image subclass shows itself in notebooks); meshes are
vertices (N, 3) float64 and faces (M, k) or flat face_vertices with face_offsets (Mesh); volumes are arrays (Z, Y, X)
with spacing and origin (Volume). Results are zero-copy views of what the C++ core made, valid for as long as any
array refers to them. Errors raise tessera.Error subclasses carrying the core's message (file, line, what was
expected): InvalidInput (also a ValueError), IoError (also an OSError), TopologyError, MemoryBudgetError. Long calls
release the GIL; `with tessera.threads(n):` caps the threads they use.
"""
import json as _json
import os as _os
import struct as _struct
import zlib as _zlib

import numpy as _np

from . import _tessera
from ._tessera import (  # noqa: F401 (the public names)
    Canvas,
    CornerTable,
    Error,
    InvalidInput,
    IoError,
    MemoryBudgetError,
    RayCaster,
    Texture,
    TopologyError,
    __version__,
    bezier,
    bezier_derivative,
    bezier_elevate,
    bezier_flatten,
    bezier_levels,
    bezier_split,
    box,
    box_counting_dimension,
    builtin_scenes,
    cantor_dust,
    cantor_set,
    color_models,
    cone,
    convert_colors,
    cube,
    cylinder,
    diamond_square,
    dodecahedron,
    face_normals,
    grid,
    height_map_mesh,
    hilbert_curve,
    icosahedron,
    julia,
    julia_is_connected,
    koch_curve,
    koch_snowflake,
    mandelbrot,
    marching_cubes,
    marching_squares,
    memory_budget,
    midpoint_displacement,
    octahedron,
    patch_control_net,
    patch_points,
    peano_curve,
    procedural_volume,
    quad_sphere,
    read_image,
    read_mesh,
    read_patches,
    read_volume,
    set_memory_budget,
    sierpinski_carpet,
    sierpinski_triangle,
    signed_volume,
    smooth,
    subdivide,
    surface_area,
    tessellate_patches,
    tetrahedron,
    thread_count,
    threads,
    to_float,
    to_uint8,
    topology,
    torus,
    triangle_mountain,
    triangulate,
    uv_sphere,
    vertex_normals,
    weld,
    window_supported,
    with_normals,
    write_image,
    write_mesh,
    write_patches,
    write_volume,
)


def _png(rgba8):
    """PNG bytes of a uint8 array (H, W, 4): what notebooks display (zlib from the standard library)."""
    height, width = rgba8.shape[:2]
    raw = b"".join(b"\x00" + rgba8[y].tobytes() for y in range(height))

    def chunk(kind, data):
        return _struct.pack(">I", len(data)) + kind + data + _struct.pack(">I", _zlib.crc32(kind + data))

    header = _struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", _zlib.compress(raw, 6)) + chunk(b"IEND", b"")


class Image(_np.ndarray):
    """A float32 image array (H, W, 3) or (H, W, 4), linear values, row 0 at the top.

    An ndarray in every respect (slice it, compute with it); a notebook shows it as a picture (_repr_png_, values
    clamped to [0, 1] without gamma, as write_image). Make one from any array with tessera.Image.of(array).
    """

    @staticmethod
    def of(array):
        """The array (H, W), (H, W, 3) or (H, W, 4) as an Image (float32; uint8 as v / 255; gray as RGB)."""
        a = _np.asarray(array)
        if a.dtype == _np.uint8:
            a = a.astype(_np.float32) / 255
        a = _np.asarray(a, dtype=_np.float32)
        if a.ndim == 2:
            a = _np.repeat(a[:, :, None], 3, axis=2)
        if a.ndim != 3 or a.shape[2] not in (3, 4):
            raise InvalidInput(f"image: expected an array (H, W), (H, W, 3) or (H, W, 4), got shape {a.shape}")
        return a.view(Image)

    def save(self, path, *, srgb=False):
        """Writes the image (write_image)."""
        write_image(_os.fspath(path), self, srgb=srgb)

    def _repr_png_(self):
        if self.ndim != 3 or self.shape[2] not in (3, 4) or self.size == 0:
            return None  # a slice that is no longer a picture: shown as an array
        return _png(to_uint8(_np.asarray(self)))


class Mesh:
    """A polygon mesh: vertices (N, 3) float64 and faces of any valence.

    Faces are stored flat, as Tessera and OpenSubdiv keep them: face_vertices (the vertex of every corner, face by
    face) and face_offsets (M + 1 entries, face f is face_vertices[face_offsets[f]:face_offsets[f + 1]]). `faces` is
    the (M, k) array when every face has k vertices. Optional per-vertex normals (N, 3), uvs (N, 2) and colors (N, 3);
    per-corner corner_uvs and corner_normals (face-varying, parallel to face_vertices); subdivision creases
    (crease_edges (K, 2), crease_sharpness (K,)) and corners (corner_vertices (C,), corner_sharpness (C,)).

    Mesh(vertices, faces) takes faces as an (M, k) array or a list of index sequences of any lengths.
    """

    _ARRAYS = ("vertices", "face_vertices", "face_offsets", "normals", "uvs", "colors", "corner_uvs",
               "corner_normals", "crease_edges", "crease_sharpness", "corner_vertices", "corner_sharpness")
    __slots__ = _ARRAYS

    def __init__(self, vertices, faces=None, *, normals=None, uvs=None, colors=None, corner_uvs=None,
                 corner_normals=None, creases=None, corners=None):
        self.vertices = _np.ascontiguousarray(vertices, dtype=_np.float64).reshape(-1, 3)
        if faces is None:
            faces = _np.zeros((0, 3), dtype=_np.uint32)
        if isinstance(faces, _np.ndarray) and faces.ndim == 2:
            self.face_vertices = _np.ascontiguousarray(faces, dtype=_np.uint32).reshape(-1)
            self.face_offsets = _np.arange(0, faces.size + 1, max(faces.shape[1], 1), dtype=_np.uint32)
        else:
            faces = [list(f) for f in faces]
            self.face_vertices = _np.array([v for f in faces for v in f], dtype=_np.uint32)
            self.face_offsets = _np.cumsum([0] + [len(f) for f in faces]).astype(_np.uint32)
        optional = {"normals": (normals, 3), "uvs": (uvs, 2), "colors": (colors, 3), "corner_uvs": (corner_uvs, 2),
                    "corner_normals": (corner_normals, 3)}
        for name, (value, k) in optional.items():
            setattr(self, name, None if value is None else _np.ascontiguousarray(value, dtype=_np.float64).reshape(-1, k))
        self.crease_edges = self.crease_sharpness = self.corner_vertices = self.corner_sharpness = None
        if creases is not None and len(creases):
            c = _np.asarray(creases, dtype=_np.float64).reshape(-1, 3)
            self.crease_edges = c[:, :2].astype(_np.uint32)
            self.crease_sharpness = c[:, 2].astype(_np.float32)
        if corners is not None and len(corners):
            c = _np.asarray(corners, dtype=_np.float64).reshape(-1, 2)
            self.corner_vertices = c[:, 0].astype(_np.uint32)
            self.corner_sharpness = c[:, 1].astype(_np.float32)

    @classmethod
    def _from_arrays(cls, vertices, face_vertices, face_offsets, normals, uvs, colors, corner_uvs, corner_normals,
                     creases, corners):
        """A Mesh over arrays the core made (no copies)."""
        mesh = cls.__new__(cls)
        mesh.vertices, mesh.face_vertices, mesh.face_offsets = vertices, face_vertices, face_offsets
        mesh.normals, mesh.uvs, mesh.colors = normals, uvs, colors
        mesh.corner_uvs, mesh.corner_normals = corner_uvs, corner_normals
        mesh.crease_edges, mesh.crease_sharpness = creases if creases is not None else (None, None)
        mesh.corner_vertices, mesh.corner_sharpness = corners if corners is not None else (None, None)
        return mesh

    @property
    def faces(self):
        """The faces as an (M, k) uint32 array (a view). Raises ValueError when faces have different valences."""
        sizes = _np.diff(self.face_offsets)
        if len(sizes) == 0:
            return self.face_vertices.reshape(0, 3)
        if not (sizes == sizes[0]).all():
            raise ValueError(f"the faces have {sizes.min()} to {sizes.max()} vertices: use face_vertices and "
                             "face_offsets (or triangulate)")
        return self.face_vertices.reshape(-1, int(sizes[0]))

    @property
    def face_count(self):
        return len(self.face_offsets) - 1

    @property
    def vertex_count(self):
        return len(self.vertices)

    def face(self, f):
        """The vertex indices of face f."""
        return self.face_vertices[self.face_offsets[f]:self.face_offsets[f + 1]]

    def __repr__(self):
        sizes = _np.unique(_np.diff(self.face_offsets))
        kinds = "/".join(str(s) for s in sizes[:4]) + ("/..." if len(sizes) > 4 else "")
        extras = [n for n in ("normals", "uvs", "colors", "corner_uvs", "corner_normals", "crease_edges",
                              "corner_vertices") if getattr(self, n) is not None]
        return (f"tessera.Mesh({self.vertex_count} vertices, {self.face_count} faces of {kinds or 0} vertices"
                + (", with " + ", ".join(extras) if extras else "") + ")")

    def _repr_png_(self):
        if self.face_count == 0:
            return None
        return render_mesh(self, size=(400, 300), background=(1, 1, 1), samples=4)._repr_png_()


class Volume:
    """Volume data: data (Z, Y, X) float32 with spacing and origin (x, y, z) in world units.

    Voxel data[k, j, i] sits at origin + spacing * (i, j, k), as VTK and ITK place them (x varies fastest in memory,
    as CT and MRI files store slices). Functions taking a volume also take a plain (Z, Y, X) array.
    """

    __slots__ = ("data", "spacing", "origin")

    def __init__(self, data, spacing=(1.0, 1.0, 1.0), origin=(0.0, 0.0, 0.0)):
        self.data = _np.asarray(data, dtype=_np.float32)
        if self.data.ndim != 3:
            raise InvalidInput(f"volume: expected an array (Z, Y, X), got shape {self.data.shape}")
        self.spacing = tuple(float(s) for s in spacing)
        self.origin = tuple(float(o) for o in origin)

    @property
    def dims(self):
        """The voxel counts (x, y, z)."""
        return tuple(reversed(self.data.shape))

    def __repr__(self):
        return f"tessera.Volume({'x'.join(map(str, self.dims))} voxels, spacing {self.spacing}, origin {self.origin})"

    def _repr_png_(self):
        return render_volume(self, size=(320, 320))._repr_png_()


def _threaded(threads, call):
    if threads is None:
        return call()
    with _tessera.threads(threads):
        return call()


def _size(size):
    width, height = size
    return int(width), int(height)


def _given(**options):
    return {k: v for k, v in options.items() if v is not None}


def render_mesh(mesh, size=(512, 512), *, shading="gouraud", color=(0.8, 0.8, 0.8), background=(0, 0, 0),
                view=None, azimuth=None, elevation=None, up_axis="y", front_axis="auto", fovy=45,
                eye=None, center=None, up=None, ortho=False, ortho_size=None, near=None, far=None, light_dir=None,
                light_pos=None, wireframe=False, cull="none", samples=1, hidden_surface="zbuffer", opacity=1.0,
                texture=None, filter="trilinear", bump=None, bump_scale=0.01, env=None, reflect=0.6,
                env_cube=False, shadows=False, shadow_method="map", shadow_size=2048, floor=False,
                vertex_shader=None, fragment_shader=None, uniforms=None, textures=None, cube_maps=None, depth=False,
                threads=None):
    """Draws a mesh with the rasterizer, as `tessera raster` does (the same pixels for the same options).

    size: (width, height). shading: 'unlit', 'flat', 'gouraud', 'phong' or 'normals'. color, background: (r, g, b) in
    [0, 1] or a name / #rrggbb. The camera frames the mesh from `view` ('three-quarter' by default, 'front', 'back',
    'left', 'right', 'top', 'bottom', 'iso') or azimuth/elevation degrees about up_axis ('x', 'y', 'z'), front_axis
    ('auto', '+x', ..., '-z'); or eye places it (not with view/azimuth/elevation); center/up, fovy, ortho/ortho_size
    and near/far replace what they name. light_dir or light_pos:
    one white light (default: over the viewer's shoulder). wireframe: edges over the surface; cull 'none' or 'back';
    samples: jittered anti-aliasing samples; hidden_surface 'zbuffer' or 'painter'; opacity < 1 blends sorted
    triangles. Maps (per pixel, Phong): texture (a path or an image array; the mesh needs uvs) with filter 'nearest',
    'bilinear' or 'trilinear'; bump (a height image) and bump_scale; env (a lat-long image) and reflect; env_cube;
    shadows with shadow_method 'map', 'zpass' or 'zfail' and shadow_size; floor. A GLSL program: vertex_shader and
    fragment_shader (file paths, or source text with newlines), uniforms {name: value(s)}, textures {unit: image},
    cube_maps {unit: lat-long image} (resampled onto six faces, as the CLI's --cube-map).

    Returns the Image (H, W, 3); with depth=True, (image, depth (H, W) window z in [0, 1], 1 = background).
    """
    options = _given(shading=shading, color=color, background=background, view=view, azimuth=azimuth,
                     elevation=elevation, up_axis=up_axis, front_axis=front_axis, fovy=fovy, eye=eye, center=center,
                     up=up, ortho=ortho, ortho_size=ortho_size, near=near, far=far, light_dir=light_dir,
                     light_pos=light_pos, wireframe=wireframe, cull=cull, samples=samples,
                     hidden_surface=hidden_surface, opacity=opacity, texture=texture, filter=filter, bump=bump,
                     bump_scale=bump_scale, env=env, reflect=reflect, env_cube=env_cube, shadows=shadows,
                     shadow_method=shadow_method, shadow_size=shadow_size, floor=floor, vertex_shader=vertex_shader,
                     fragment_shader=fragment_shader, uniforms=uniforms, textures=textures,
                     cube_maps=cube_maps)
    for key in ("texture", "bump", "env"):
        if isinstance(options.get(key), _os.PathLike):
            options[key] = _os.fspath(options[key])
    width, height = _size(size)
    image, depth_image, _ = _threaded(threads, lambda: _tessera._render_mesh(mesh, width, height, options))
    return (image, depth_image) if depth else image


def render_volume(volume, size=(256, 256), *, transfer=None, mip=False, step=None, shading=True,
                  background=(0, 0, 0), view=None, azimuth=None, elevation=None, up_axis="y",
                  front_axis="auto", fovy=30, eye=None, center=None, up=None, ortho=False, ortho_size=None,
                  threads=None):
    """Ray-casts a volume (direct volume rendering, as `tessera volume render`): front-to-back compositing of the
    transfer function's colors and opacities with gradient shading, or mip=True for a maximum-intensity projection.

    transfer: None (automatic: Otsu's threshold of the values), a preset name, a .json/.csv file, or rows
    (value, r, g, b, opacity): opacity in [0, 1] is that of a unit length of the medium. step: sample distance in world units (default half the smallest
    spacing). The camera options frame the volume's box as render_mesh frames a mesh. Returns the Image (H, W, 3).
    """
    options = _given(transfer=None if transfer is None else (_os.fspath(transfer) if isinstance(transfer, _os.PathLike)
                                                             else transfer),
                     mip=mip, step=step, shading=shading, background=background, view=view, azimuth=azimuth,
                     elevation=elevation, up_axis=up_axis, front_axis=front_axis, fovy=fovy, eye=eye, center=center,
                     up=up, ortho=ortho, ortho_size=ortho_size)
    width, height = _size(size)
    return _threaded(threads, lambda: _tessera._render_volume(volume, width, height, options))


class Scene:
    """A scene (docs/scene-format.md): a built-in name (tessera.builtin_scenes), a .json file or a dict. render()
    draws it as render_scene does; a notebook shows a one-sample ray-traced preview at the scene's own size."""

    def __init__(self, source):
        self.source = source

    def render(self, size=None, **options):
        """render_scene(self.source, size, **options)."""
        return render_scene(self.source, size, **options)

    @property
    def frames(self):
        """The frames the scene spans, a range (range(0, 1) for a still scene; docs/scene-format.md "Animation")."""
        first, last, _, _, _ = _tessera._scene_animation(*_scene_source(self.source))
        return range(first, last + 1)

    @property
    def fps(self):
        """The scene's frames per second."""
        return _tessera._scene_animation(*_scene_source(self.source))[2]

    def __repr__(self):
        return f"tessera.Scene({self.source!r})" if not isinstance(self.source, dict) else "tessera.Scene({...})"

    def _repr_png_(self):
        return self.render(samples=1)._repr_png_()


def _scene_source(scene):
    """(source, is_text, base folder) of a scene given as a Scene, a built-in name, a .json path or a dict."""
    if isinstance(scene, Scene):
        scene = scene.source
    if isinstance(scene, dict):
        return _json.dumps(scene), True, _os.getcwd()
    return _os.fspath(scene), False, ""


def render_scene(scene, size=None, *, samples=None, depth=None, seed=0, backend="raytrace", frame=None, threads=None):
    """Renders a scene (docs/scene-format.md) with the ray tracer (backend 'raytrace': recursive and distribution
    ray tracing) or the rasterizer ('raster'), as `tessera render` does.

    scene: a built-in name (tessera.builtin_scenes), a .json file, or a dict in the scene format (paths in it relative
    to the working folder). size (width, height), samples (per pixel) and depth (recursion) replace the scene's own.
    frame: the frame of an animated scene (its keyed values there; Scene(...).frames lists them), by default its
    first. Returns the Image (H, W, 3), linear.
    """
    source, is_text, base = _scene_source(scene)
    width, height = (None, None) if size is None else _size(size)
    return _threaded(threads, lambda: _tessera._render_scene(source, is_text, base, width, height, samples, depth,
                                                             seed, backend, frame))
