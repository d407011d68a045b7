"""Makes the pictures of docs/python.md with the installed tessera package.

    .venv/bin/python docs/python/make_pictures.py OUTDIR [NAME ...]

(any interpreter with the package installed: docs/python.md, "Install"). Reads the shared data from
$TESSERA_SHARED_DATA (default: ../shared/data next to the repository) and the GLSL programs from examples/shaders. A
picture whose data is missing is skipped with a note. NAMEs (e.g. spot) make only those pictures. The calls are the
guide's examples; the pictures are small (each under 60 KB).
"""
import os
import pathlib
import sys

import numpy as np

import tessera

ROOT = pathlib.Path(__file__).resolve().parents[2]
DATA = pathlib.Path(os.environ.get("TESSERA_SHARED_DATA", ROOT.parent / "shared" / "data"))
SHADERS = ROOT / "examples" / "shaders"

PICTURES = []


def picture(name, *needs):
    """Registers a function returning (image, srgb) as the picture `name`.png; `needs` are shared data paths."""

    def register(make):
        PICTURES.append((name, [DATA / n for n in needs], make))
        return make

    return register


def row(*images):
    """Images of the same height side by side (RGB)."""
    return np.concatenate([np.asarray(i)[..., :3] for i in images], axis=1)


def column(*images):
    return np.concatenate([np.asarray(i)[..., :3] for i in images], axis=0)


# Images and colors --------------------------------------------------------------------------------------------------

@picture("colors", "textures/coffee.png")
def colors():
    photo = tessera.read_image(DATA / "textures/coffee.png")  # Image (400, 600, 4), values v / 255
    hsv = tessera.convert_colors(photo[..., :3], "rgb", "hsv")  # (400, 600, 3), hue in turns
    hsv[..., 0] = (hsv[..., 0] + 1 / 3) % 1  # hue turned by a third
    hsv[..., 1] *= 1.3
    shifted = tessera.convert_colors(np.clip(hsv, 0, 1), "hsv", "rgb")
    # Both at a quarter of the size (the mean of 4 x 4 blocks), for the guide.
    small = [a.reshape(100, 4, 150, 4, 3).mean(axis=(1, 3)) for a in (photo[..., :3], shifted)]
    return row(*small), False  # the photo's values are sRGB-encoded already: written as they are


# Meshes ------------------------------------------------------------------------------------------------------------

@picture("bunny", "meshes/bunny/bun_zipper_res2.ply", "meshes/bunny/bun_zipper_res4.ply")
def bunny():
    bunny = tessera.read_mesh(DATA / "meshes/bunny/bun_zipper_res2.ply")
    lit = tessera.render_mesh(bunny, (240, 200), color=(0.85, 0.6, 0.4), background="white", front_axis="-x",
                              samples=4)
    coarse = tessera.read_mesh(DATA / "meshes/bunny/bun_zipper_res4.ply")
    facets = tessera.render_mesh(coarse, (240, 200), shading="flat", wireframe=True, color="lightsteelblue",
                                 background="white", front_axis="-x", samples=4)
    return row(lit, facets), True


@picture("primitives")
def primitives():
    meshes = [tessera.tetrahedron(), tessera.cube(), tessera.octahedron(), tessera.dodecahedron(),
              tessera.icosahedron(), tessera.box(), tessera.uv_sphere(16, 8), tessera.quad_sphere(4),
              tessera.cylinder(16), tessera.cone(16), tessera.torus(1.0, 0.4, 24, 12), tessera.grid(6, 6)]
    tiles = [tessera.render_mesh(m, (120, 100), shading="flat", wireframe=True, color="lightsteelblue",
                                 background="white", samples=4) for m in meshes]
    return column(row(*tiles[:4]), row(*tiles[4:8]), row(*tiles[8:])), True


@picture("smoothing", "meshes/bunny/bun_zipper_res2.ply")
def smoothing():
    bunny = tessera.read_mesh(DATA / "meshes/bunny/bun_zipper_res2.ply")
    rng = np.random.default_rng(1)
    noisy = tessera.Mesh(bunny.vertices + rng.normal(0, 0.0008, bunny.vertices.shape), bunny.faces)
    laplacian = tessera.smooth(noisy, "laplacian", iterations=10)  # shrinks
    taubin = tessera.smooth(noisy, "taubin", iterations=10)  # keeps the volume
    style = dict(color=(0.85, 0.6, 0.4), background="white", front_axis="-x", samples=4)
    return row(*[tessera.render_mesh(m, (160, 160), **style) for m in (noisy, laplacian, taubin)]), True


# Subdivision -------------------------------------------------------------------------------------------------------

@picture("subdivision", "meshes/spot/spot_control_mesh.obj")
def subdivision():
    cage = tessera.read_mesh(DATA / "meshes/spot/spot_control_mesh.obj")  # 180 faces of 3, 4 and 5 vertices
    smooth = tessera.subdivide(cage, "catmull-clark", levels=3, limit=True)  # 11,712 quads on the limit surface
    loop = tessera.subdivide(tessera.tetrahedron(), "loop", levels=4)
    style = dict(color="lightsteelblue", background="white", samples=4)
    return row(tessera.render_mesh(cage, (160, 160), wireframe=True, shading="flat", front_axis="-z", **style),
               tessera.render_mesh(smooth, (160, 160), front_axis="-z", **style),
               tessera.render_mesh(loop, (160, 160), **style)), True


@picture("creases")
def creases():
    cube = tessera.cube()
    top = cube.faces[2]  # the face y = +1
    tiles = []
    for sharpness in (0, 1, 2, 10):  # 10 and above: infinitely sharp
        rim = [(top[i], top[(i + 1) % 4], sharpness) for i in range(4)] if sharpness else None
        creased = tessera.Mesh(cube.vertices, cube.faces, creases=rim)
        smooth = tessera.subdivide(creased, levels=4)
        tiles.append(tessera.render_mesh(smooth, (120, 120), color="lightsteelblue", background="white",
                                         view="front", elevation=25, samples=4))
    return row(*tiles), True


# Volumes -----------------------------------------------------------------------------------------------------------

def head():
    """The headsq CT turned upright: its slices stack from the top of the head down, so z is flipped (and y, to
    keep a rotation rather than a mirror image)."""
    ct = tessera.read_volume(str(DATA / "volumes/headsq_64x64x93_int16le.mhd"))
    return tessera.Volume(ct.data[::-1, ::-1], ct.spacing, ct.origin)


@picture("volume", "volumes/headsq_64x64x93_int16le.mhd")
def volume():
    ct = head()
    view = dict(up_axis="z", azimuth=150, elevation=15)
    skin = tessera.render_volume(ct, (160, 200), transfer="ct-skin", **view)
    bone = tessera.render_volume(ct, (160, 200), transfer="ct-bone", **view)
    mip = tessera.render_volume(ct, (160, 200), mip=True, up_axis="z", view="back")
    return row(skin, bone, mip), True


@picture("isosurface", "volumes/headsq_64x64x93_int16le.mhd")
def isosurface():
    skin = tessera.marching_cubes(head(), iso=500)
    gyroid = tessera.marching_cubes(tessera.procedural_volume("gyroid:48"), iso=0.0)
    return row(tessera.render_mesh(skin, (200, 200), up_axis="z", azimuth=150, elevation=15,
                                   color=(0.9, 0.75, 0.65), background="white", samples=4),
               tessera.render_mesh(gyroid, (200, 200), color="lightsteelblue", background="white", samples=4)), True


def draw_lines(image, lines, color, scale):
    """Draws marching_squares polylines (x, y in field pixels) into an image `scale` times the field's size."""
    for points, closed in lines:
        p = points * scale + (scale - 1) / 2
        if closed:
            p = np.vstack([p, p[:1]])
        for a, b in zip(p[:-1], p[1:]):
            steps = int(np.ceil(np.abs(b - a).max())) + 1
            xy = np.rint(a + (b - a) * np.linspace(0, 1, steps)[:, None]).astype(int)
            for dx, dy in ((0, 0), (1, 0), (0, 1), (1, 1)):  # 2 pixels wide
                rows = np.minimum(xy[:, 1] + dy, image.shape[0] - 1)
                columns = np.minimum(xy[:, 0] + dx, image.shape[1] - 1)
                image[rows, columns] = color


@picture("contours", "volumes/headsq_64x64x93_int16le.mhd")
def contours():
    ct = tessera.read_volume(str(DATA / "volumes/headsq_64x64x93_int16le.mhd"))
    slice_ = ct.data[46]  # (64, 64): the slice z = 46
    skin = tessera.marching_squares(slice_, iso=500)  # [(points (K, 2), closed), ...]
    bone = tessera.marching_squares(slice_, iso=1150)
    scale = 4
    gray = np.repeat(np.repeat(slice_ / slice_.max(), scale, 0), scale, 1)
    image = np.repeat(gray[:, :, None], 3, axis=2)
    draw_lines(image, skin, (1.0, 0.8, 0.2), scale)
    draw_lines(image, bone, (0.2, 0.6, 1.0), scale)
    return image, False


# Rendering ---------------------------------------------------------------------------------------------------------

@picture("spot", "meshes/spot/spot_triangulated.obj", "meshes/spot/spot_texture.png")
def spot():
    cow = tessera.read_mesh(DATA / "meshes/spot/spot_triangulated.obj")  # corner_uvs from the file
    textured = tessera.render_mesh(cow, (200, 200), texture=DATA / "meshes/spot/spot_texture.png", shading="phong",
                                   front_axis="-z", background="white", samples=4)
    program = tessera.render_mesh(cow, (200, 200), vertex_shader=SHADERS / "notes_texture.vert",
                                  fragment_shader=SHADERS / "notes_texture.frag", uniforms={"myTexture": 0},
                                  textures={0: DATA / "meshes/spot/spot_texture.png"}, front_axis="-z",
                                  background="white", samples=4)
    return row(textured, program), False  # the texture holds sRGB-encoded values (read_image does not decode)


@picture("maps", "meshes/bunny/bun_zipper_res2.ply", "env/venice_sunset_1k.hdr", "textures/brick.png")
def maps():
    bunny = tessera.read_mesh(DATA / "meshes/bunny/bun_zipper_res2.ply")
    shadowed = tessera.render_mesh(bunny, (160, 160), shadows=True, floor=True, light_dir=(-1, 2, 1),
                                   color=(0.85, 0.6, 0.4), background="white", front_axis="-x", samples=4)
    mirror = tessera.render_mesh(tessera.torus(), (160, 160), env=DATA / "env/venice_sunset_1k.hdr", reflect=0.9,
                                 color=(0.1, 0.1, 0.1), elevation=35, samples=4)
    bumpy = tessera.render_mesh(tessera.torus(), (160, 160), bump=DATA / "textures/brick.png", bump_scale=0.02,
                                shading="phong", color=(0.8, 0.5, 0.4), background="white", elevation=35,
                                samples=4)
    return row(shadowed, mirror, bumpy), True


@picture("shaders", "meshes/bunny/bun_zipper_res2.ply")
def shaders():
    bunny = tessera.read_mesh(DATA / "meshes/bunny/bun_zipper_res2.ply")
    toon = tessera.render_mesh(bunny, (200, 200), vertex_shader=SHADERS / "toon.vert",
                               fragment_shader=SHADERS / "toon.frag", uniforms={"base_color": (0.9, 0.5, 0.2)},
                               light_dir=(0, 1, 0), background="white", front_axis="-x", samples=4)
    bricks = tessera.render_mesh(bunny, (200, 200), vertex_shader=SHADERS / "brick.vert",
                                 fragment_shader=SHADERS / "brick.frag",
                                 uniforms={"brick_color": (0.7, 0.2, 0.1), "mortar_color": (0.8, 0.8, 0.75),
                                           "brick_size": (0.02, 0.01), "brick_pct": (0.85, 0.8)},
                                 background="white", front_axis="-x", samples=4)
    return row(toon, bricks), True


SCENE = {
    "camera": {"eye": [0, 1.5, 5], "center": [0, 0.6, 0], "fovy": 40},
    "lights": [{"type": "point", "position": [3, 5, 4]}],
    "materials": {
        "floor": {"diffuse": 0.8, "checker": {"size": 0.5, "color": 0.3}},
        "red": {"diffuse": [0.8, 0.15, 0.1], "specular": 0.5, "shininess": 60},
        "mirror": {"diffuse": 0.05, "specular": 0.6, "reflection": 0.8},
    },
    "objects": [
        {"type": "plane", "material": "floor"},
        {"type": "sphere", "center": [-0.7, 0.6, 0], "radius": 0.6, "material": "red"},
        {"type": "sphere", "center": [0.8, 0.6, -0.5], "radius": 0.6, "material": "mirror"},
    ],
}


@picture("scenes")
def scenes():
    whitted = tessera.render_scene("whitted", (160, 120), samples=16)
    cornell = tessera.render_scene("cornell", (160, 120), samples=64)
    raster = tessera.render_scene("mesh", (160, 120), backend="raster")
    mine = tessera.render_scene(SCENE, (160, 120), samples=4)
    return column(row(whitted, cornell), row(raster, mine)), True


@picture("raycast", "meshes/bunny/bun_zipper_res2.ply")
def raycast():
    bunny = tessera.read_mesh(DATA / "meshes/bunny/bun_zipper_res2.ply")
    caster = tessera.RayCaster(bunny)
    width, height = 240, 180
    lo, hi = bunny.vertices.min(axis=0), bunny.vertices.max(axis=0)
    eye = (lo + hi) / 2 + [0, 0, 0.3]  # on +z, looking down -z
    y, x = np.mgrid[0:height, 0:width] + 0.5
    half = np.tan(np.radians(15))  # half of a 30 degree field of view
    directions = np.stack([(2 * x / width - 1) * half * width / height, (1 - 2 * y / height) * half,
                           -np.ones_like(x)], axis=-1).reshape(-1, 3)
    origins = np.broadcast_to(eye, directions.shape)
    t, triangle, barycentric = caster.cast(origins, directions)  # (N,), (N,), (N, 2)
    hit = triangle >= 0
    normals = tessera.face_normals(bunny)[np.where(hit, triangle, 0)]
    image = np.where(hit[:, None], 0.5 + 0.5 * normals, 1.0).reshape(height, width, 3)
    return image, False


# The canvas and sketches ----------------------------------------------------------------------------------------------

@picture("canvas")
def canvas():
    canvas = tessera.Canvas(320, 160)
    canvas.background(250)
    canvas.stroke(40)
    canvas.stroke_weight(3)
    canvas.fill(255, 150, 150)
    canvas.rect(20, 30, 90, 90)
    canvas.fill(90, 150, 230, 180)
    canvas.ellipse(130, 80, 110, 110)
    canvas.no_fill()
    canvas.begin_shape()
    canvas.vertex(200, 130)
    canvas.bezier_vertex(220, 10, 300, 10, 300, 130)
    canvas.end_shape()
    canvas.fill(40)
    canvas.text_size(16)
    canvas.text("canvas", 210, 150)
    return canvas.picture, False


@picture("sketch")
def sketch():
    from tessera import sketch as ts

    class Orbit(ts.Sketch):
        """A square orbiting the center, its trail fading: frames 10, 20, 30 side by side."""

        def setup(self):
            self.size(120, 120)
            self.background(255)

        def draw(self):
            self.no_stroke()
            self.fill(255, 255, 255, 40)
            self.rect(0, 0, 120, 120)
            angle = self.frame_count * 0.2
            self.fill(255, 150, 150)
            self.rect(60 + 35 * np.cos(angle) - 10, 60 + 35 * np.sin(angle) - 10, 20, 20)

    frames = []
    ts.run_sketch(Orbit(), frames=30, on_frame=lambda n, rgba: frames.append(rgba) if n % 10 == 0 else None)
    return row(*[f.astype(np.float32) / 255 for f in frames]), False


# Curves, patches and fractals ---------------------------------------------------------------------------------------

@picture("curves", "bezier/teapot.bpt")
def curves():
    points = np.array([[20, 140], [60, 20], [200, 20], [240, 140]], float)
    canvas = tessera.Canvas(260, 160)
    canvas.background(255)
    canvas.stroke(180)
    canvas.stroke_weight(1)
    for level in tessera.bezier_levels(points, 0.4)[:-1]:  # de Casteljau's construction at t = 0.4
        for a, b in zip(level[:-1], level[1:]):
            canvas.line(*a, *b)
    canvas.stroke(200, 40, 40)
    canvas.stroke_weight(2)
    curve = tessera.bezier(points, np.linspace(0, 1, 64))
    for a, b in zip(curve[:-1], curve[1:]):
        canvas.line(*a, *b)
    canvas.no_stroke()
    canvas.fill(40)
    x, y = tessera.bezier(points, [0.4])[0]
    canvas.ellipse(x, y, 7, 7)
    patches = tessera.read_patches(DATA / "bezier/teapot.bpt")
    teapot = tessera.tessellate_patches(patches, 8, orientation="outward")
    pot = tessera.render_mesh(teapot, (240, 160), up_axis="z", shading="phong", color="goldenrod",
                              background="white", samples=4)
    return row(np.asarray(canvas.picture)[..., :3], pot), True


@picture("fractals")
def fractals():
    mandelbrot = tessera.mandelbrot((240, 160), center=-0.745 + 0.11j, scale=0.12, iterations=800)
    julia = tessera.julia(-0.8 + 0.156j, (240, 160), palette="ocean")
    canvas = tessera.Canvas(160, 160)
    canvas.background(255)
    canvas.fill(60, 110, 200)
    canvas.no_stroke()
    canvas.begin_shape()
    for x, y in tessera.koch_snowflake(4):
        canvas.vertex(20 + 120 * x, 130 - 120 * y)
    canvas.end_shape(True)
    return row(mandelbrot, julia, np.asarray(canvas.picture)[..., :3]), False


def main(argv):
    if len(argv) < 2:
        sys.exit(__doc__)
    out = pathlib.Path(argv[1])
    out.mkdir(parents=True, exist_ok=True)
    wanted = set(argv[2:])
    for name, needs, make in PICTURES:
        if wanted and name not in wanted:
            continue
        missing = [str(n) for n in needs if not n.exists()]
        if missing:
            print(f"{name}.png: skipped, missing {', '.join(missing)}")
            continue
        image, srgb = make()
        path = out / f"{name}.png"
        tessera.write_image(path, image, srgb=srgb)
        print(f"{path}: {image.shape[1]}x{image.shape[0]}, {path.stat().st_size // 1024} KB")


if __name__ == "__main__":
    main(sys.argv)
