"""Figures of the unloaded TCA (lsbg.figures.contact_state): panels, scales and what they show.

The bearing-pattern and transmission-error figures are drawn from real TCA
datasets (40 positions, about a third of a second each once numba has
compiled); the V-H maps from small synthetic datasets. Every figure also
passes the report checks of tests/figures/test_base.py (labels with units, width,
nothing cut or overprinted, legends off the data).
"""

import re

import numpy as np
import pytest
import xarray as xr
from matplotlib.colors import to_rgb
from matplotlib.contour import QuadContourSet
from matplotlib.figure import Figure
from matplotlib.patches import Ellipse

from lsbg.gear.design import GearPairDesign
from lsbg.figures import contact_state
from lsbg.figures.base import MAX_WIDTH, type_color
from lsbg.gear.geometry import GearPair
from lsbg.tca.analysis import tooth_contact_analysis
from lsbg.tca.modification import FlankModification
from tests.figures.test_base import assert_readable

UNIT = re.compile(r"\[[^\]]+\]")
POSITIONS = 40


@pytest.fixture(scope="module")
def tcas():
    out = {}
    for label, trace in (("LSBG 35°", "logarithmic"), ("SBG 35°", "circular")):
        pair = GearPair(GearPairDesign.from_config(dict(trace=trace, spiral_angle_deg=35)))
        out[label] = tooth_contact_analysis(pair, FlankModification(25e-6, 5e-6),
                                            positions=POSITIONS)
    return out


#: V-H map variables: (units, long_name).
MAP_VARIABLES = {
    "transmission_error_unloaded_pp": ("urad", "peak-to-peak unloaded transmission error"),
    "transmission_error_loaded_pp": ("urad", "peak-to-peak loaded transmission error"),
    "pattern_cone_distance": ("mm", "pattern centre: cone distance"),
    "pattern_height": ("mm", "pattern centre: height above the root cone"),
    "pattern_shift_lengthwise": ("mm", "lengthwise shift of the pattern centre"),
    "pattern_shift_profile": ("mm", "profile shift of the pattern centre"),
    "pattern_length": ("mm", "pattern length"),
    "edge_contact_share": ("1", "share of positions with edge contact"),
    "edge_load_share": ("1", "share of the load at an edge"),
}


def vh_map(scale, dims=("P", "G")):
    """A 3 x 4 V-H map over two displacements, every variable ``scale`` times a bowl
    (not square: a map drawn with its dimensions swapped fails)."""
    units = {"E": "mm", "P": "mm", "G": "mm", "Sigma": "degree"}
    x, y = np.array([-0.1, 0.0, 0.1]), np.array([-0.05, 0.0, 0.025, 0.05])
    bowl = 1.0 + 40 * x[:, None] ** 2 + 20 * y[None, :] ** 2 + 3 * x[:, None]
    return xr.Dataset(
        {name: (dims, scale * bowl, {"units": unit, "long_name": long_name})
         for name, (unit, long_name) in MAP_VARIABLES.items()},
        coords={dims[0]: (dims[0], x, {"units": units.get(dims[0], "1")}),
                dims[1]: (dims[1], y, {"units": units.get(dims[1], "1")})})


@pytest.fixture
def maps():
    return {"LSBG 35°": vh_map(1.0), "SBG 35°": vh_map(2.5)}


def panels(fig):
    """The data panels: every axes but the colour bars."""
    return [ax for ax in fig.axes if getattr(ax, "_colorbar", None) is None]


def colour_bars(fig):
    return [ax for ax in fig.axes if getattr(ax, "_colorbar", None) is not None]


def check_figure(fig, n_panels):
    assert isinstance(fig, Figure)
    assert fig.get_size_inches()[0] <= MAX_WIDTH
    assert len(panels(fig)) == n_panels
    for ax in panels(fig):
        assert UNIT.search(ax.get_xlabel()), ax.get_xlabel()
        assert UNIT.search(ax.get_ylabel()), ax.get_ylabel()
    for ax in colour_bars(fig):
        assert UNIT.search(ax.get_ylabel()), ax.get_ylabel()
    assert_readable(fig)


def contour_sets(ax):
    return [c for c in ax.collections if isinstance(c, QuadContourSet)]


# ------------------------------------------------------------ bearing pattern
@pytest.mark.parametrize("count", [5, 3])
def test_bearing_pattern_panels_pattern_and_ellipses(tcas, count):
    fig = contact_state.bearing_pattern(tcas, ellipses=count)
    check_figure(fig, len(tcas))
    assert len(colour_bars(fig)) == 1 and "µm" in colour_bars(fig)[0].get_ylabel()
    assert fig.legends, "the legend above the panels is missing"
    for ax, (label, ds) in zip(panels(fig), tcas.items()):
        assert label in ax.get_title()
        assert f"{ds.attrs['transmission_error_peak_to_peak_arcsec']:.3g} arcsec" in ax.get_title()
        assert sum(isinstance(p, Ellipse) for p in ax.patches) == count
        marking = ds.attrs["marking_compound_um"]
        # the pattern: a contour set filled up to the marking thickness, in the type's colour
        fills = [c for c in contour_sets(ax) if c.levels[-1] == pytest.approx(marking)]
        assert len(fills) == 1 and len(fills[0].get_paths()[0].vertices) > 3
        assert np.allclose(fills[0].get_facecolor()[0][:3],
                           to_rgb(type_color(ds.attrs["design_trace"])))
        # ... spanning the pattern's toe to heel as the analysis reports them (to a raster cell)
        x = fills[0].get_paths()[0].vertices[:, 0]
        step = float(np.diff(ds["cone_distance"].values[:2])[0])
        assert x.min() == pytest.approx(ds.attrs["pattern_toe_mm"], abs=1.5 * step)
        assert x.max() == pytest.approx(ds.attrs["pattern_heel_mm"], abs=1.5 * step)
        # the shaded separation starts at the marking thickness
        assert any(c.levels[0] == pytest.approx(marking) and len(c.levels) > 2
                   for c in contour_sets(ax))
        texts = {t.get_text(): t.get_position()[0] for t in ax.texts}
        assert texts["toe"] < texts["heel"]


def test_flank_outline_is_the_active_flank(tcas):
    fig = contact_state.bearing_pattern(tcas)
    for ax, ds in zip(panels(fig), tcas.values()):
        outlines = [line for line in ax.lines if len(line.get_xdata()) == 5]
        assert len(outlines) == 1
        x, y = (np.asarray(v, dtype=float) for v in outlines[0].get_data())
        half = ds.attrs["face_width_mm"] / 2
        assert x.min() == pytest.approx(ds.attrs["mean_cone_distance_mm"] - half, abs=1e-9)
        assert x.max() == pytest.approx(ds.attrs["mean_cone_distance_mm"] + half, abs=1e-9)
        assert (x[0], y[0]) == (x[-1], y[-1])
        height = ds["profile_height"].values
        assert y.min() < height.min() and y.max() > height.max()
        # the path of contact is drawn, broken where the tooth in contact changes
        path = [line for line in ax.lines if len(line.get_xdata()) >= POSITIONS]
        assert len(path) == 1
        drawn = np.asarray(path[0].get_xdata(), dtype=float)
        assert np.array_equal(drawn[np.isfinite(drawn)], ds["contact_cone_distance"].values)


def test_bearing_pattern_grows_with_a_thicker_marking(tcas):
    def pattern_length(fig, ds, marking):
        ax = panels(fig)[0]
        fill = [c for c in contour_sets(ax) if c.levels[-1] == pytest.approx(marking)][0]
        x = np.concatenate([p.vertices[:, 0] for p in fill.get_paths()])
        return np.ptp(x)

    one = {"LSBG 35°": tcas["LSBG 35°"]}
    default = tcas["LSBG 35°"].attrs["marking_compound_um"]
    thin = pattern_length(contact_state.bearing_pattern(one), one["LSBG 35°"], default)
    thick = pattern_length(contact_state.bearing_pattern(one, marking=3 * default),
                           one["LSBG 35°"], 3 * default)
    assert thick > thin + 1.0


# -------------------------------------------------------- transmission error
def test_transmission_error_two_cycles_of_each_pair(tcas):
    fig = contact_state.transmission_error(tcas)
    check_figure(fig, 1)
    ax = panels(fig)[0]
    assert "µrad" in ax.get_ylabel()
    lines = [line for line in ax.lines if len(line.get_xdata()) > 2]
    assert len(lines) == len(tcas)
    for line, ds in zip(lines, tcas.values()):
        x, y = (np.asarray(v, dtype=float) for v in line.get_data())
        assert x.size == 2 * POSITIONS + 1 and x.max() - x.min() == pytest.approx(2.0)
        te = ds["transmission_error"].values
        assert np.allclose(y[:POSITIONS], te) and np.allclose(y[POSITIONS:2 * POSITIONS], te)
    labels = [t.get_text() for legend in fig.legends for t in legend.get_texts()]
    assert len(labels) == len(tcas)
    for text, (label, ds) in zip(labels, tcas.items()):
        assert text.startswith(label)
        assert f"{ds.attrs['transmission_error_peak_to_peak_urad']:.3g} µrad" in text


# ---------------------------------------------------------- misalignment map
@pytest.mark.parametrize("quantity", ["transmission_error_unloaded_pp", "pattern_shift_lengthwise",
                                      "edge_contact_share"])
def test_misalignment_map_shares_one_colour_scale(maps, quantity):
    fig = contact_state.misalignment_map(maps, quantity)
    check_figure(fig, len(maps))
    bars = colour_bars(fig)
    assert len(bars) == 1
    unit, long_name = MAP_VARIABLES[quantity]
    shown = {"urad": "µrad", "mm": "mm", "1": "-"}[unit]
    assert long_name.split()[0] in bars[0].get_ylabel() and f"[{shown}]" in bars[0].get_ylabel()
    sets = [contour_sets(ax) for ax in panels(fig)]
    assert all(len(s) == 1 for s in sets)
    sets = [s[0] for s in sets]
    first = sets[0]
    for other in sets[1:]:
        assert other.get_clim() == first.get_clim()
        assert np.array_equal(other.levels, first.levels)
    low, high = first.get_clim()
    everything = np.concatenate([ds[quantity].values.ravel() for ds in maps.values()])
    assert low <= everything.min() and high >= everything.max()
    # one scale covering both, not each panel's own: the SBG map reaches 2.5 times as far
    assert high >= maps["SBG 35°"][quantity].values.max() > maps["LSBG 35°"][quantity].values.max()
    for ax, (label, ds) in zip(panels(fig), maps.items()):
        assert ax.get_title() == label
        assert ax.get_xlabel() == "pinion axial P [mm]"
        assert ax.get_ylabel() == "gear axial G [mm]"
        aligned = [line for line in ax.lines if line.get_marker() == "+"]
        assert len(aligned) == 1 and list(aligned[0].get_xdata()) == [0.0]
        assert list(aligned[0].get_ydata()) == [0.0]


def test_misalignment_map_first_dimension_across(maps):
    turned = {"LSBG 35°": vh_map(1.0, ("Sigma", "E"))}
    fig = contact_state.misalignment_map(turned, "pattern_length")
    check_figure(fig, 1)
    ax = panels(fig)[0]
    assert ax.get_xlabel() == "shaft-angle error Σ [deg]"
    assert ax.get_ylabel() == "offset E [mm]"
    assert ax.get_xlim() == pytest.approx((-0.1, 0.1))


def test_misalignment_map_refuses_what_is_not_a_map(maps):
    with pytest.raises(ValueError, match="no variable 'stiffness'"):
        contact_state.misalignment_map(maps, "stiffness")
    odd = {"odd": vh_map(1.0, ("P", "speed"))}
    with pytest.raises(ValueError, match="a V-H map has two of"):
        contact_state.misalignment_map(odd, "pattern_length")
