"""Colors against Python's colorsys; images against PIL and the CLI."""
import colorsys
import io

import numpy as np
import pytest
from PIL import Image as PILImage

import tessera


@pytest.mark.parametrize("model,forward", [("hsv", colorsys.rgb_to_hsv), ("hls", colorsys.rgb_to_hls),
                                           ("yiq", colorsys.rgb_to_yiq)])
def test_convert_colors_matches_colorsys(model, forward):
    rgb = np.random.default_rng(7).random((1000, 3))
    ours = tessera.convert_colors(rgb, "rgb", model)
    reference = np.array([forward(*c) for c in rgb])
    if model in ("hsv", "hls"):  # hue is circular: 0 and 1 are the same turn
        d = np.abs(ours[:, 0] - reference[:, 0])
        assert np.minimum(d, 1 - d).max() < 1e-9
        assert np.abs(ours[:, 1:] - reference[:, 1:]).max() < 1e-9
    else:
        assert np.abs(ours - reference).max() < 1e-6
    back = tessera.convert_colors(ours, model, "rgb")
    assert np.abs(back - rgb).max() < 1e-6


def test_convert_colors_keeps_leading_shape_and_hue_units():
    rgb = np.array([[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]])
    hsv = tessera.convert_colors(rgb, "rgb", "hsv", hue="degrees")
    assert hsv.shape == (1, 2, 3)
    assert hsv[0, 1, 0] == pytest.approx(120.0)
    assert tessera.convert_colors([0.0, 0.0, 0.0], "rgb", "cmyk").shape == (4,)
    with pytest.raises(tessera.InvalidInput, match="expected one of|unknown color model"):
        tessera.convert_colors(rgb, "rgb", "hsx")
    with pytest.raises(ValueError, match=r"\(\.\.\., 3\)"):
        tessera.convert_colors(np.zeros((4, 2)), "rgb", "hsv")


def test_png_bytes_match_pil(tmp_path):
    rng = np.random.default_rng(1)
    pixels = rng.integers(0, 256, (37, 53, 4), dtype=np.uint8)
    tessera.write_image(tmp_path / "a.png", pixels)
    assert np.array_equal(np.asarray(PILImage.open(tmp_path / "a.png").convert("RGBA")), pixels)
    PILImage.fromarray(pixels, "RGBA").save(tmp_path / "b.png")
    read = tessera.read_image(tmp_path / "b.png")
    assert isinstance(read, tessera.Image) and read.shape == (37, 53, 4) and read.dtype == np.float32
    assert np.abs(read * 255 - pixels).max() < 1e-3
    assert np.array_equal(tessera.read_image(tmp_path / "b.png", dtype="uint8"), pixels)


def test_float_images_round_and_clamp_like_the_cli(tmp_path, cli):
    image = tessera.Image.of(np.linspace(-0.5, 1.5, 64 * 3, dtype=np.float32).reshape(8, 8, 3))
    expected = np.clip(np.rint(np.clip(image, 0, 1) * 255), 0, 255).astype(np.uint8)
    assert np.array_equal(tessera.to_uint8(image)[..., :3], expected)
    tessera.write_image(tmp_path / "p.pfm", image)
    cli("color", "--help")  # the CLI runs: the comparisons below use its own reader
    assert np.allclose(tessera.read_image(tmp_path / "p.pfm")[..., :3], image)
    srgb = tessera.to_uint8(tessera.Image.of(np.full((1, 1, 3), 0.5, np.float32)), srgb=True)
    assert srgb[0, 0, 0] == 188  # the sRGB curve at 0.5: 0.7354 * 255


def test_repr_png_is_a_png_of_the_image():
    image = tessera.Image.of(np.tile(np.linspace(0, 1, 16, dtype=np.float32)[None, :, None], (4, 1, 3)))
    decoded = np.asarray(PILImage.open(io.BytesIO(image._repr_png_())).convert("RGBA"))
    assert np.array_equal(decoded, tessera.to_uint8(image))
    assert image[0, 0]._repr_png_() is None  # a pixel is not a picture


def test_image_errors_name_the_file(tmp_path):
    with pytest.raises(tessera.IoError, match="missing.png"):
        tessera.read_image(tmp_path / "missing.png")
    (tmp_path / "bad.png").write_bytes(b"\x89PNG\r\n\x1a\nnot really")
    with pytest.raises(tessera.InvalidInput, match="bad.png"):
        tessera.read_image(tmp_path / "bad.png")
    with pytest.raises(tessera.InvalidInput, match="extension|format"):
        tessera.write_image(tmp_path / "a.xyz", np.zeros((2, 2, 3), np.float32))
    assert not list(tmp_path.glob("a.xyz*"))
    with pytest.raises(ValueError, match=r"\(H, W\)"):
        tessera.write_image(tmp_path / "a.png", np.zeros((2, 2, 5), np.float32))


def test_textures_sample_as_the_notes_say():
    texels = np.array([[[255, 0, 0, 255], [0, 255, 0, 255]], [[0, 0, 255, 255], [255, 255, 255, 255]]], np.uint8)
    nearest = tessera.Texture(texels, filter="nearest")
    # v runs upward: v = 0.75 is the top row (row 0 of the image).
    assert np.array_equal(nearest.sample([[0.25, 0.75], [0.75, 0.75], [0.25, 0.25]]),
                          [[1, 0, 0, 1], [0, 1, 0, 1], [0, 0, 1, 1]])
    bilinear = tessera.Texture(texels, filter="bilinear", wrap="clamp")
    center = bilinear.sample([[0.5, 0.5]])[0]
    assert np.allclose(center, texels.reshape(4, 4).mean(axis=0) / 255, atol=1 / 255)
    assert nearest.levels == 2 and nearest.level(1).shape == (1, 1, 4)
    trilinear = tessera.Texture(texels, filter="trilinear")
    assert np.allclose(trilinear.sample([[0.3, 0.6]], lod=1)[0], texels.reshape(4, 4).mean(axis=0) / 255, atol=1 / 255)
    with pytest.raises(tessera.InvalidInput, match="wrap: expected one of"):
        tessera.Texture(texels, wrap="tile")


def test_memory_budget_refuses_up_front():
    try:
        tessera.set_memory_budget(1 << 20)
        assert tessera.memory_budget() == 1 << 20
        with pytest.raises(MemoryError, match="budget"):
            tessera.render_mesh(tessera.cube(), size=(4000, 4000))
        with pytest.raises(tessera.MemoryBudgetError):
            tessera.procedural_volume("sphere:400")
    finally:
        tessera.set_memory_budget(0)
    assert tessera.memory_budget() > 1 << 20
