"""Picture of the assembled pair: a compiled z-buffer rasterizer of its solids.

The geometry stage writes one picture per design point. Drawing the ~46 000
triangles of the two solids as matplotlib polygons would take about half the
stage's time; rasterizing them here with a depth buffer (numba, compiled once per
machine into the on-disk cache) takes milliseconds and hides faces
correctly where the painter's order of whole triangles cannot. The image is
rendered at twice its size and averaged down (anti-aliasing), then written
with its caption by Pillow.
"""

from __future__ import annotations

import math
import os

import numpy as np
from numba import njit

from lsbg.gear.geometry import MEMBERS

__all__ = ["rasterize", "render_pair"]

#: Flat colours of the members (pinion, gear) [RGB, 0-1].
COLOURS = {1: (0.85, 0.50, 0.22), 2: (0.55, 0.62, 0.75)}
#: The caption's name of each tooth trace.
PICTURE_TRACES = {"logarithmic": "LSBG (logarithmic spiral)", "circular": "SBG (circular arc)",
                  "face_milled": "SBG (ISO 23509 face-milled)"}
#: Ambient share of the Lambert shading [-].
AMBIENT = 0.35


@njit(cache=True)
def rasterize(screen, depth, colours, image, zbuffer):
    """Draw triangles into ``image`` where they are nearer than ``zbuffer``.

    Parameters
    ----------
    screen : numpy.ndarray, shape (n, 3, 2)
        Vertices in pixel coordinates (x to the right, y down) [pixel].
    depth : numpy.ndarray, shape (n, 3)
        Distance of each vertex along the view direction (smaller is nearer)
        [any length unit].
    colours : numpy.ndarray, shape (n, 3)
        Flat colour of each triangle [RGB, 0-1].
    image : numpy.ndarray, shape (height, width, 3)
        Written in place.
    zbuffer : numpy.ndarray, shape (height, width)
        Depth of the nearest triangle so far (start with +inf); updated.

    Returns
    -------
    int
        Pixels written [-].
    """
    height, width = zbuffer.shape
    written = 0
    for t in range(screen.shape[0]):
        x0, y0 = screen[t, 0, 0], screen[t, 0, 1]
        x1, y1 = screen[t, 1, 0], screen[t, 1, 1]
        x2, y2 = screen[t, 2, 0], screen[t, 2, 1]
        area = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0)
        if area == 0.0:
            continue
        lo_x = max(int(math.floor(min(x0, x1, x2))), 0)
        hi_x = min(int(math.ceil(max(x0, x1, x2))), width - 1)
        lo_y = max(int(math.floor(min(y0, y1, y2))), 0)
        hi_y = min(int(math.ceil(max(y0, y1, y2))), height - 1)
        for py in range(lo_y, hi_y + 1):
            cy = py + 0.5
            for px in range(lo_x, hi_x + 1):
                cx = px + 0.5
                # barycentric weights by edge functions; either winding
                w0 = ((x1 - cx) * (y2 - cy) - (x2 - cx) * (y1 - cy)) / area
                w1 = ((x2 - cx) * (y0 - cy) - (x0 - cx) * (y2 - cy)) / area
                w2 = 1.0 - w0 - w1
                if w0 < 0.0 or w1 < 0.0 or w2 < 0.0:
                    continue
                z = w0 * depth[t, 0] + w1 * depth[t, 1] + w2 * depth[t, 2]
                if z < zbuffer[py, px]:
                    zbuffer[py, px] = z
                    image[py, px, 0] = colours[t, 0]
                    image[py, px, 1] = colours[t, 1]
                    image[py, px, 2] = colours[t, 2]
                    written += 1
    return written


def _downsample(image, factor):
    """Sums of ``factor`` x ``factor`` pixel blocks, shape (height / factor, width / factor, 3).

    Bit for bit ``image.reshape(h, factor, w, factor, 3).sum(axis=(1, 3))``
    (the picture's bytes stay the same): numpy adds a block's pixels one by
    one in memory order, as here, but its strided reduction is several times
    slower. tests/solid/test_render.py checks the order.

    Parameters
    ----------
    image : numpy.ndarray, shape (height, width, 3)
        [any]
    factor : int
        Block size [pixel].

    Returns
    -------
    numpy.ndarray
        Same dtype as ``image`` [same unit].
    """
    height, width = image.shape[0] // factor, image.shape[1] // factor
    blocks = image.reshape(height, factor, width, factor, image.shape[2])
    total = blocks[:, 0, :, 0].copy()
    for row in range(factor):
        for col in range(factor):
            if row or col:
                total += blocks[:, row, :, col]
    return total


def render_pair(path, pair, meshes, size=(900, 700), supersample=2):
    """PNG picture of the assembled pair (both gears at rotation 0).

    An orthographic view of the gear's tooth face with the pinion in mesh,
    flat-shaded (Lambert with an ambient part), hidden faces removed by the
    depth buffer of :func:`rasterize`, captioned with the design.

    Parameters
    ----------
    path : str or os.PathLike
        PNG file to write.
    pair : lsbg.gear.geometry.GearPair
        Its design is the caption.
    meshes : dict
        ``{member: lsbg.solid.polyhedra.TriangleMesh}`` for members 1 and 2 [m].
    size : tuple of int
        Width and height [pixel].
    supersample : int
        Rendered at this multiple of ``size`` and averaged down [-].

    Returns
    -------
    str
        The path written.
    """
    from PIL import Image, ImageDraw, ImageFont

    d = pair.design
    # Look at the gear's tooth face (from its apex side, against a2), a little
    # towards the heel and from above the axial plane, so the pinion shows in mesh.
    view = -0.9 * pair.axis[2] + 0.3 * pair.pitch_dir + np.array([0.0, 0.0, 0.55])
    view /= np.linalg.norm(view)
    right = np.cross([0.0, 0.0, 1.0], view)
    right /= np.linalg.norm(right)
    up = np.cross(view, right)
    light = np.array([0.3, 0.6, 0.75])
    light /= np.linalg.norm(light)
    triangles, colours = [], []
    for member in MEMBERS:
        mesh = meshes[member]
        normals = mesh.face_normals
        facing = normals @ view > 0   # back faces are hidden by the solid anyway
        triangles.append(mesh.vertices[mesh.faces[facing]])   # gathers the facing half only
        lambert = np.clip(normals[facing] @ light, 0.0, 1.0)
        colours.append((AMBIENT + (1 - AMBIENT) * lambert)[:, None] * np.array(COLOURS[member]))
    triangles, colours = np.concatenate(triangles), np.concatenate(colours)

    caption = 0.08                       # share of the height kept for the caption
    width, height = size[0] * supersample, size[1] * supersample
    margin = 0.02 * width
    plane = np.stack([triangles @ right, triangles @ up], axis=-1)
    lo, hi = plane.reshape(-1, 2).min(axis=0), plane.reshape(-1, 2).max(axis=0)
    scale = min((width - 2 * margin) / (hi[0] - lo[0]),
                (height * (1 - caption) - 2 * margin) / (hi[1] - lo[1]))
    screen = np.empty_like(plane)
    screen[..., 0] = 0.5 * width + scale * (plane[..., 0] - 0.5 * (lo[0] + hi[0]))
    screen[..., 1] = (height * caption + 0.5 * height * (1 - caption)
                      - scale * (plane[..., 1] - 0.5 * (lo[1] + hi[1])))
    # the view vector points towards the viewer: nearer is larger along it
    depth = -(triangles @ view)
    # single precision: the supersampled buffers are large (1800 x 1400 here)
    image = np.ones((height, width, 3), dtype=np.float32)
    zbuffer = np.full((height, width), np.inf, dtype=np.float32)
    rasterize(np.ascontiguousarray(screen), np.ascontiguousarray(depth),
              np.ascontiguousarray(colours), image, zbuffer)
    image = _downsample(image, supersample)
    image *= 255.0 / supersample**2
    picture = Image.fromarray(np.round(image).astype(np.uint8), "RGB")
    text = (f"{PICTURE_TRACES[d.trace]}, spiral angle {math.degrees(d.spiral_angle):g}°, "
            f"{d.pinion_teeth}:{d.gear_teeth}, m = {1e3 * d.module:g} mm")
    draw = ImageDraw.Draw(picture)
    font = ImageFont.load_default(size=round(0.03 * size[1]))
    left, top, box_right, bottom = draw.textbbox((0, 0), text, font=font)
    draw.text(((size[0] - (box_right - left)) / 2, 0.02 * size[1]), text, fill=(0, 0, 0),
              font=font)
    picture.save(os.fspath(path), format="PNG")
    return os.fspath(path)
