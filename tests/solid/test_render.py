"""The pair's picture: the z-buffer rasterizer and the rendered PNG."""

import numpy as np
import pytest

from lsbg.solid import outline, render, solids
from lsbg.gear.design import GearPairDesign
from lsbg.gear.geometry import GearPair


def _blank(height=40, width=60):
    return np.ones((height, width, 3)), np.full((height, width), np.inf)


def test_a_triangle_covers_its_area():
    image, z = _blank()
    screen = np.array([[[10.0, 10.0], [50.0, 10.0], [10.0, 30.0]]])
    written = render.rasterize(screen, np.zeros((1, 3)), np.array([[1.0, 0.0, 0.0]]), image, z)
    # pixel centres inside a right triangle of legs 40 and 20: about 400
    assert written == pytest.approx(0.5 * 40 * 20, rel=0.06)
    assert (image[..., 1] == 0.0).sum() == written
    assert tuple(image[12, 12]) == (1.0, 0.0, 0.0)
    assert tuple(image[28, 48]) == (1.0, 1.0, 1.0)   # beyond the hypotenuse


@pytest.mark.parametrize("order", [(0, 1), (1, 0)])
def test_the_nearer_triangle_hides_the_farther_in_either_order(order):
    image, z = _blank()
    square = np.array([[[0.0, 0.0], [60.0, 0.0], [0.0, 40.0]], [[60.0, 0.0], [60.0, 40.0], [0.0, 40.0]]])
    # two overlapping triangles, the blue one nearer (smaller depth)
    screen = np.array([square[0], square[0]])[list(order)]
    depth = np.array([[2.0] * 3, [1.0] * 3])[list(order)]
    colours = np.array([[1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])[list(order)]
    render.rasterize(screen, depth, colours, image, z)
    assert tuple(image[5, 5]) == (0.0, 0.0, 1.0)
    assert z[5, 5] == 1.0


def test_depth_is_interpolated_across_a_triangle():
    image, z = _blank()
    screen = np.array([[[0.0, 0.0], [60.0, 0.0], [0.0, 40.0]]])
    render.rasterize(screen, np.array([[0.0, 60.0, 0.0]]), np.array([[0.5, 0.5, 0.5]]), image, z)
    # depth grows linearly with x (0 at x = 0, 60 at x = 60), at pixel centres
    assert z[2, 10] == pytest.approx(10.5)
    assert z[2, 30] == pytest.approx(30.5)


def test_picture_of_the_pair_shows_both_members(tmp_path):
    from PIL import Image

    pair = GearPair(GearPairDesign())
    meshes = solids.gear_meshes(pair, outline.MeshResolution(chord_tolerance=1e-3, twist_step=0.2))
    path = render.render_pair(tmp_path / "pair.png", pair, meshes, size=(300, 240))
    pixels = np.asarray(Image.open(path).convert("RGB")).astype(float) / 255
    assert pixels.shape == (240, 300, 3)
    # the members' flat colours, shaded: the pinion reddish, the gear bluish
    pinion = (pixels[..., 0] > pixels[..., 2] + 0.15).mean()
    gear = (pixels[..., 2] > pixels[..., 0] + 0.05).mean()
    assert pinion > 0.01 and gear > 0.05
    # background white around, caption dark at the top
    assert pixels[-1, -1].tolist() == [1.0, 1.0, 1.0]
    assert pixels[:30].min() < 0.3


@pytest.mark.parametrize("factor", [1, 2, 3, 4])
def test_downsample_is_bit_for_bit_the_numpy_block_sum(factor):
    rng = np.random.default_rng(factor)
    shape = (70 * factor, 50 * factor, 3)
    # float32 sums of mixed magnitudes: any other order of addition shows
    image = (rng.random(shape) * rng.choice([1e-4, 1.0, 1e4], shape)).astype(np.float32)
    expected = image.reshape(70, factor, 50, factor, 3).sum(axis=(1, 3))
    blocks = render._downsample(image, factor)
    assert blocks.dtype == expected.dtype and np.array_equal(blocks, expected)
