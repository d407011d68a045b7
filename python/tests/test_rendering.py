"""Rendering: the same pixels as the CLI for the same options; ray casting against analytic intersections."""
import numpy as np
import pytest

import tessera


def test_render_mesh_equals_the_cli(tmp_path, cli):
    torus = tessera.torus(1.0, 0.35, 40, 20)
    tessera.write_mesh(tmp_path / "torus.obj", torus)
    cli("raster", tmp_path / "torus.obj", "-o", tmp_path / "cli.png", "--size", "96x64", "--shading", "phong",
        "--color", "orange", "--view", "top", "--samples", 4)
    ours = tessera.render_mesh(torus, size=(96, 64), shading="phong", color="orange", view="top", samples=4)
    tessera.write_image(tmp_path / "py.png", ours)
    assert (tmp_path / "py.png").read_bytes() == (tmp_path / "cli.png").read_bytes()
    image, depth = tessera.render_mesh(torus, size=(96, 64), depth=True)
    assert depth.shape == (64, 96) and depth.min() < 1 and depth[0, 0] == 1


def test_render_mesh_textured_and_glsl_equal_the_cli(tmp_path, cli, shared_data):
    spot = shared_data / "meshes" / "spot" / "spot_triangulated.obj"
    texture = spot.with_name("spot_texture.png")
    if not spot.exists():
        pytest.skip(f"no {spot}")
    cli("raster", spot, "-o", tmp_path / "cli.png", "--size", "80x60", "--texture", texture, "--front-axis", "-z")
    ours = tessera.render_mesh(tessera.read_mesh(spot), size=(80, 60), texture=texture, front_axis="-z")
    tessera.write_image(tmp_path / "py.png", ours)
    assert (tmp_path / "py.png").read_bytes() == (tmp_path / "cli.png").read_bytes()

    vert = "void main() { gl_Position = ftransform(); }\n"
    frag = "uniform vec3 paint;\nvoid main() { gl_FragColor = vec4(paint, 1.0); }\n"
    flat = tessera.render_mesh(tessera.cube(), size=(32, 32), vertex_shader=vert, fragment_shader=frag,
                               uniforms={"paint": (0.2, 0.4, 0.6)})
    unlit = tessera.render_mesh(tessera.cube(), size=(32, 32), shading="unlit", color=(0.2, 0.4, 0.6))
    assert np.array_equal(tessera.to_uint8(flat), tessera.to_uint8(unlit))
    with pytest.raises(tessera.InvalidInput, match="fragment shader:2"):
        tessera.render_mesh(tessera.cube(), vertex_shader=vert, fragment_shader="void main() {\n  oops;\n}\n")


def test_render_scene_equals_the_cli(tmp_path, cli):
    assert "whitted" in tessera.builtin_scenes
    cli("render", "whitted", "-o", tmp_path / "cli.png", "--size", "64x48", "--spp", 1, "--quiet")
    tessera.write_image(tmp_path / "py.png", tessera.render_scene("whitted", size=(64, 48), samples=1))
    assert (tmp_path / "py.png").read_bytes() == (tmp_path / "cli.png").read_bytes()
    scene = {"camera": {"eye": [0, 0, 5], "center": [0, 0, 0]},
             "image": {"size": [24, 24]},
             "lights": [{"type": "point", "position": [3, 3, 5]}],
             "materials": {"red": {"diffuse": [1, 0, 0]}},
             "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "red"}]}
    image = tessera.render_scene(scene)
    assert image.shape == (24, 24, 3) and image[12, 12, 0] > 0.3 and image[12, 12, 1] < 0.05
    with pytest.raises(tessera.InvalidInput, match="radius"):
        scene["objects"][0]["radius"] = -1
        tessera.render_scene(scene)


def test_frames_of_an_animated_scene_equal_the_cli(tmp_path, cli):
    scene = tessera.Scene("whitted-moving")
    assert scene.frames == range(0, 48) and scene.fps == 24
    assert tessera.Scene("whitted").frames == range(0, 1)
    cli("render", "whitted-moving", "--frames", "11:12", "-o", tmp_path / "f_%02d.pfm", "--size", "40x30", "--spp", 2,
        "--quiet")
    for frame in (11, 12):
        image = tessera.render_scene("whitted-moving", size=(40, 30), samples=2, frame=frame)
        assert np.array_equal(image, tessera.read_image(tmp_path / f"f_{frame}.pfm")[..., :3])
    assert not np.array_equal(tessera.render_scene("whitted-moving", (40, 30), samples=2, frame=0),
                              tessera.render_scene("whitted-moving", (40, 30), samples=2, frame=12))
    with pytest.raises(tessera.InvalidInput, match="frame 48 is outside the scene's frames 0..47"):
        tessera.render_scene("whitted-moving", (8, 6), frame=48)
    keyed = {"animation": {"frames": [0, 10]},
             "camera": {"eye": {"keys": [[0, [0, 0, 5]], [10, [0, 0, 3]]]}, "center": [0, 0, 0]},
             "materials": {"m": {"diffuse": 0.8}},
             "objects": [{"type": "sphere", "radius": 1, "material": "m"}]}
    assert tessera.Scene(keyed).frames == range(0, 11)
    near, far = (tessera.render_scene(keyed, (32, 32), frame=f) for f in (10, 0))
    assert (near.sum(axis=2) > 0.05).sum() > (far.sum(axis=2) > 0.05).sum()  # the sphere grows as the eye nears


def test_ray_casting_hits_the_box_where_planes_say():
    caster = tessera.RayCaster(tessera.box())
    rng = np.random.default_rng(3)
    n = 5000
    origins = rng.uniform(-0.9, 0.9, (n, 3)) * [1, 1, 0] + [0, 0, 4]
    directions = rng.normal(size=(n, 3)) * 0.1 + [0, 0, -1]
    t, prim, uv = caster.cast(origins, directions)
    # Analytic: the slab intersection of the box [-1, 1]^3 (entry distance).
    with np.errstate(divide="ignore"):
        t0, t1 = (-1 - origins) / directions, (1 - origins) / directions
    enter, leave = np.minimum(t0, t1).max(axis=1), np.maximum(t0, t1).min(axis=1)
    hit = enter <= leave
    assert np.array_equal(prim >= 0, hit)
    assert np.abs(t[hit] - enter[hit]).max() < 1e-4 and np.isinf(t[~hit]).all()
    assert caster.triangle_count == 12 and uv.shape == (n, 2)
    t_near, _, _ = caster.cast(origins, directions, tmax=2.0)
    assert np.isinf(t_near).all()


def test_unknown_options_and_threads():
    with pytest.raises(TypeError):
        tessera.render_mesh(tessera.cube(), shadng="flat")
    with pytest.raises(tessera.InvalidInput, match="shading: expected one of"):
        tessera.render_mesh(tessera.cube(), shading="toon")
    with tessera.threads(1):
        assert tessera.thread_count() == 1
        one = tessera.render_mesh(tessera.cube(), size=(40, 40))
    assert np.array_equal(one, tessera.render_mesh(tessera.cube(), size=(40, 40), threads=2))


def test_camera_options_are_checked_as_the_cli_checks_them():
    with pytest.raises(tessera.InvalidInput, match="eye: it places the camera"):
        tessera.render_mesh(tessera.cube(), size=(8, 8), eye=(0, 3, 4), view="top")
    eye = tessera.render_mesh(tessera.cube(), size=(24, 24), eye=(0, 0, 5), center=(0, 0, 0))
    front = tessera.render_mesh(tessera.cube(), size=(24, 24), view="front")
    assert eye.shape == front.shape == (24, 24, 3)


def test_scene_objects_show_a_preview():
    scene = tessera.Scene("whitted")
    assert repr(scene) == "tessera.Scene('whitted')"
    preview = scene.render(size=(32, 24), samples=1)
    assert preview.shape == (24, 32, 3)
    assert np.array_equal(preview, tessera.render_scene("whitted", size=(32, 24), samples=1))
