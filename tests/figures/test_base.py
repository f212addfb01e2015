"""Every report figure reads well at report size: labels with units, nothing cut or overprinted.

Each figure function of :mod:`lsbg.figures` is drawn (Agg, 100 dpi, as
:func:`lsbg.figures.base.figure_png` renders it into a report) and checked by one
helper, :func:`readability_problems`:

(a) every visible axes with data has an x and a y label, with a unit in square
    brackets where the axis is numeric (an axis of categories names them
    instead; colour bars and secondary axes label their one axis);
(b) no two drawn tick labels of one axis overlap, nor any two texts of the
    figure (labels, titles, legends, tick labels of neighbouring panels);
(c) no text lies outside the figure (it would be cut off in the PNG);
(d) the PNG is at most 1340 px wide (reports are read at 1400 px);
(e) no legend lies on an axes' data area.

The data are small: synthetic tables, and the short real runs, loaded TCAs and
geometry of the session fixture ``runs`` (tests/conftest.py).
"""

import io
import re
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import xarray as xr
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.layout_engine import ConstrainedLayoutEngine
from matplotlib.text import Text
from matplotlib.ticker import FixedFormatter, FuncFormatter

from lsbg.figures import (geometry as geometry_figures, mesh as mesh_figures,
                          spectra as spectra_figures, speed as speed_figures,
                          statistics as statistics_figures, timeseries as timeseries_figures,
                          trends as trend_figures, verification as verification_figures)
from lsbg.figures.base import axis_label, display_unit, wrap_label
from lsbg.solid.directory import read_design
from lsbg.figures.base import figure_png
from lsbg.dynamics.dataset import open_run
from lsbg.aggregate.runs import open_mesh
from lsbg.tables import line_model as line_tables, paper as paper_tables
from lsbg.tables import verification as verification_tables
from lsbg.experiments import point_checks

#: Widest PNG a report shows at full size [px].
MAX_WIDTH_PX = 1340
#: A unit in square brackets: "[deg/s]", "[-]", "[%]", "[10⁻⁵/N]".
UNIT = re.compile(r"\[[^\]]+\]")
START = 0.01   # end of the transient of the fixture's 0.05-s runs [s]


# ------------------------------------------------------------------ the check
def _drawn_tick_labels(axis):
    """The tick labels an axis draws: visible, not empty, at ticks inside the view."""
    if not axis.get_visible():
        return []
    # compare in the axis' scale (log10 on a log axis), to a millionth of the view
    scale = axis.get_transform()
    low, high = sorted(np.ravel(scale.transform(np.reshape(axis.get_view_interval(), (-1, 1)))))
    slack = 1e-6 * (high - low)
    labels = []
    for ticks, locations in ((axis.get_major_ticks(), axis.get_majorticklocs()),
                             (axis.get_minor_ticks(), axis.get_minorticklocs())):
        for tick, location in zip(ticks, locations):
            where = float(np.ravel(scale.transform([[location]]))[0])
            if low - slack <= where <= high + slack:
                labels += [label for label in (tick.label1, tick.label2)
                           if label.get_visible() and label.get_text().strip()]
    return labels


def _all_tick_labels(axis):
    """Every tick label the axis holds, drawn or not (it keeps spare ticks beyond its locations)."""
    return [label for tick in list(axis.majorTicks) + list(axis.minorTicks)
            for label in (tick.label1, tick.label2)]


def _is_number(text):
    try:
        float(text.replace("−", "-"))
    except ValueError:
        return False
    return True


def _categorical(axis):
    """An axis of named categories: tick labels set by hand (``set_xticks(ticks, labels)``
    gives a fixed or function formatter) that are not numbers."""
    return (isinstance(axis.get_major_formatter(), (FixedFormatter, FuncFormatter))
            and any(not _is_number(label.get_text()) for label in _drawn_tick_labels(axis)))


def _label_problem(where, axis):
    """What is wrong with an axis' label, or None."""
    text = axis.get_label().get_text().strip()
    if not _drawn_tick_labels(axis):
        return None   # no scale shown (a shared axis labelled on its neighbour)
    if not text:
        return f"{where}: no label"
    if _categorical(axis):
        return None
    if not UNIT.search(text):
        return f"{where}: label {text!r} has no unit in [brackets]"
    if re.search(r"\[[^\]]*\b(urad|um)\b", text):
        return f"{where}: label {text!r} writes µ as u"
    return None


def _overlapping(texts, renderer, slack=0.5):
    boxes = [(t, t.get_window_extent(renderer)) for t in texts]
    pairs = []
    for i, (a, box_a) in enumerate(boxes):
        for b, box_b in boxes[i + 1:]:
            width = min(box_a.x1, box_b.x1) - max(box_a.x0, box_b.x0)
            height = min(box_a.y1, box_b.y1) - max(box_a.y0, box_b.y0)
            if width > slack and height > slack:
                pairs.append((a.get_text(), b.get_text()))
    return pairs


def render(fig):
    """Draw a figure as a report does; return its PNG width [px] and the Agg renderer."""
    from PIL import Image

    width = Image.open(io.BytesIO(figure_png(fig, palette=False))).size[0]
    fig.set_dpi(100)
    FigureCanvasAgg(fig)
    fig.canvas.draw()
    return width, fig.canvas.get_renderer()


def readability_problems(fig):
    """Everything that keeps a figure from reading well in a report, as sentences.

    Parameters
    ----------
    fig : matplotlib.figure.Figure

    Returns
    -------
    list of str
        Empty if the figure passes checks (a)–(e) of this module.
    """
    problems = []
    width, renderer = render(fig)
    if width > MAX_WIDTH_PX:
        problems.append(f"the PNG is {width} px wide (at most {MAX_WIDTH_PX})")
    axes = [ax for ax in fig.axes if ax.get_visible()]
    every = axes + [child for ax in axes for child in ax.child_axes if child.get_visible()]
    # (a) labels
    for k, ax in enumerate(axes):
        name = f"axes {k} ({ax.get_title() or ax.get_ylabel()!r})"
        if not ax.axison or not ax.has_data():
            continue
        colorbar = getattr(ax, "_colorbar", None)
        if colorbar is not None:
            axis = ax.yaxis if colorbar.orientation == "vertical" else ax.xaxis
            problems.append(_label_problem(f"{name} colour bar", axis))
            continue
        problems += [_label_problem(f"{name} x axis", ax.xaxis),
                     _label_problem(f"{name} y axis", ax.yaxis)]
        for child in ax.child_axes:
            orientation = getattr(child, "_orientation", "x")
            axis = child.xaxis if orientation == "x" else child.yaxis
            problems.append(_label_problem(f"{name} secondary {orientation} axis", axis))
    # (b) tick labels overprinting each other
    for k, ax in enumerate(every):
        for axis in (ax.xaxis, ax.yaxis):
            for a, b in _overlapping(_drawn_tick_labels(axis), renderer):
                problems.append(f"axes {k}: tick labels {a!r} and {b!r} overlap")
    # (c) text outside the figure
    ticks = {id(label) for ax in every for axis in (ax.xaxis, ax.yaxis)
             for label in _all_tick_labels(axis)}
    texts = [t for t in fig.findobj(Text) if id(t) not in ticks]
    texts += [label for ax in every for axis in (ax.xaxis, ax.yaxis)
              for label in _drawn_tick_labels(axis)]
    if isinstance(fig.get_layout_engine(), ConstrainedLayoutEngine):
        bounds = fig.bbox
    else:   # figure_png saves these with a tight bounding box: nothing is cut
        bounds = fig.get_tightbbox(renderer).transformed(fig.dpi_scale_trans)
    for text in texts:
        if not text.get_visible() or not text.get_text().strip():
            continue
        box = text.get_window_extent(renderer)
        if (box.x0 < bounds.x0 - 1 or box.y0 < bounds.y0 - 1 or box.x1 > bounds.x1 + 1
                or box.y1 > bounds.y1 + 1):
            problems.append(f"text {text.get_text()!r} is cut off at the figure's edge")
    # (b') texts running into each other: labels, titles, tick labels of neighbouring
    # panels, legend entries (a legend's entries are laid out apart by construction)
    drawn = [t for t in texts if t.get_visible() and t.get_text().strip()]
    for a, b in _overlapping(drawn, renderer, slack=1.0):
        problems.append(f"texts {a!r} and {b!r} overlap")
    # (e) legends on data
    legends = list(fig.legends) + [ax.get_legend() for ax in axes if ax.get_legend()]
    for legend in legends:
        box = legend.get_window_extent(renderer)
        for k, ax in enumerate(axes):
            if not ax.axison or getattr(ax, "_colorbar", None) is not None:
                continue
            area = ax.bbox
            width = min(box.x1, area.x1) - max(box.x0, area.x0)
            height = min(box.y1, area.y1) - max(box.y0, area.y0)
            if width > 1 and height > 1:
                problems.append(f"a legend lies on the data of axes {k}")
    return [p for p in problems if p]


def assert_readable(fig):
    assert isinstance(fig, Figure)
    problems = readability_problems(fig)
    assert not problems, "\n".join(problems)


# ------------------------------------------------ the check itself can fail
def _bad(kind):
    fig = Figure(figsize=(4, 3), layout="constrained")
    ax = fig.subplots()
    ax.plot([0, 1, 2], [0, 1, 4], label="data")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("force [N]")
    if kind == "no unit":
        ax.set_ylabel("force")
    elif kind == "ascii micro":
        ax.set_ylabel("transmission error [urad]")
    elif kind == "no label":
        ax.set_xlabel("")
    elif kind == "overlapping ticks":
        ax.set_xticks(np.arange(12) / 6, [f"category number {k}" for k in range(12)])
        ax.set_xlabel("category")
    elif kind == "cut off":
        ax.set_ylabel("a label far longer than the axes is tall, so it runs past both "
                      "edges of the figure [N]")
    elif kind == "too wide":
        fig.set_size_inches(14, 3)
    elif kind == "legend on data":
        ax.legend(loc="upper left")
    elif kind == "labels collide":
        fig.set_size_inches(4, 4.5)
        below = fig.add_subplot(2, 1, 2)
        ax.set_subplotspec(fig.add_gridspec(2, 1)[0])
        below.plot([0, 1], [1, 0])
        below.set_xlabel("time [s]")
        for panel in (ax, below):
            panel.set_ylabel("a label longer than its panel [N]")
    return fig


@pytest.mark.parametrize("kind, message", [
    ("no unit", "has no unit"), ("ascii micro", "writes µ as u"), ("no label", "no label"),
    ("overlapping ticks", "overlap"), ("cut off", "cut off"), ("too wide", "px wide"),
    ("legend on data", "legend lies on the data"),
    ("labels collide", "and 'a label longer than its panel [N]' overlap")])
def test_the_check_finds_what_a_reader_would(kind, message):
    problems = readability_problems(_bad(kind))
    assert any(message in p for p in problems), problems
    assert not readability_problems(_bad("good"))


def test_labels_print_units_as_a_reader_reads_them():
    assert display_unit("urad") == "µrad" and display_unit("N/um") == "N/µm"
    assert display_unit("N/(mm um)") == "N/(mm·µm)" and display_unit("1") == "-"
    assert axis_label("transmission error", "urad") == "transmission error [µrad]"
    wrapped = wrap_label("gear-speed fluctuation [% of mean]", 26)
    assert wrapped.splitlines()[-1].replace("\u00a0", " ") == "[% of mean]"


# ------------------------------------------------------------------- data
@pytest.fixture(scope="module")
def point_runs(runs):
    return {"SBG": open_run(runs["sbg35"]), "LSBG": open_run(runs["lsbg35"])}


@pytest.fixture(scope="module")
def line_runs(runs):
    return {"SBG": open_run(runs["sbg35_line"]), "LSBG": open_run(runs["lsbg35_line"])}


@pytest.fixture(scope="module")
def meshes(runs):
    return {"SBG": open_mesh(runs["sbg35_mesh"]), "LSBG": open_mesh(runs["lsbg35_mesh"])}


@pytest.fixture(scope="module")
def geometry_dirs(runs):
    root = Path(runs["lsbg35"]).parent.parent / "geometry"
    return {"SBG": root / "sbg35", "LSBG": root / "lsbg35"}


def _angles():
    return np.arange(20.0, 45.1, 2.5)


@pytest.fixture(scope="module")
def sweep_table():
    """A sweep_fluctuation_table-like table: both models, both types, 11 spiral angles."""
    rng = np.random.default_rng(0)
    rows = []
    for model in ("point", "line"):
        for label in ("SBG", "LSBG"):
            for angle in _angles():
                row = {"contact_model": model, "gear_type": label, "spiral_angle_deg": angle}
                for quantity, scale in (("gear_speed", 5.0), ("tangential_force", 200.0),
                                        ("transmission_error", 20.0)):
                    std = scale * (1 + rng.random()) * (8 if model == "point" else 1)
                    row.update({f"{quantity}_std": std, f"{quantity}_std_low": 0.95 * std,
                                f"{quantity}_std_high": 1.05 * std,
                                f"{quantity}_sampled_std": std * (1 + 0.1 * rng.normal())})
                row.update(dynamic_factor=1.1, static_transmission_error_peak_to_peak=150.0,
                           static_transmission_error_harmonic_1=60.0,
                           mesh_stiffness_variation=15.0, mesh_stiffness_per_face_width=20.0,
                           contact_ratio=2.0 + angle / 30)
                rows.append(row)
    return pd.DataFrame(rows)


@pytest.fixture(scope="module")
def speed_curve():
    """A speed_curve-like dataset: two traces, eight speeds, a peak at the resonance."""
    speeds = np.geomspace(2e4, 2e5, 8)
    frequency = np.linspace(10.0, 6000.0, 120)
    natural = np.array([1825.0, 1832.0])
    teeth = 9
    mesh = speeds / 360 * teeth
    peak = np.exp(-np.log(mesh[None, :] / natural[:, None]) ** 2 / 0.05)
    orders = np.array([1, 2, 3])
    return xr.Dataset(
        {"mesh_frequency": ("pinion_speed", mesh),
         "natural_frequency": ("trace", natural),
         "resonance_speed": (("trace", "order"), natural[:, None] / orders * 360 / teeth),
         "dte_spectrum": (("trace", "pinion_speed", "frequency"),
                          np.exp(-((frequency[None, None, :] - mesh[None, :, None]) / 50) ** 2)
                          * 100 * (1 + peak[:, :, None])),
         "dte_rms": (("trace", "pinion_speed"), 50 * (1 + 5 * peak)),
         "dynamic_factor": (("trace", "pinion_speed"), 1 + 0.8 * peak),
         "gear_speed_fluctuation": (("trace", "pinion_speed"), 0.3 * (1 + 5 * peak))},
        coords={"trace": ["circular", "logarithmic"], "pinion_speed": speeds, "order": orders,
                "frequency": frequency},
        attrs={"design_pinion_teeth": teeth})


@pytest.fixture(scope="module")
def agreement():
    """Twelve engine comparisons, as the verification report stacks them (both models)."""
    rows = []
    for model, engine in (("point", "pybullet"), ("line", "scipy")):
        for label in ("SBG", "LSBG"):
            for quantity in ("gear_speed", "tangential_force", "tangential_force_outer"):
                ratio = 1.015 if model == "point" else 1.00002
                rows.append({"gear_type": label, "spiral_angle_deg": 35.0, "engine": engine,
                             "reference": "compiled", "quantity": quantity, "std": ratio,
                             "reference_std": 1.0, "std_ratio": ratio,
                             "mean_difference_percent": 0.01, "within_tolerance": True,
                             "contact_model": model})
    rows[2].update(std_ratio=1.05, within_tolerance=False)
    return pd.DataFrame(rows)


# ----------------------------------------------------------------- geometry
def test_pair_pictures_without_the_caption_strip(geometry_dirs):
    from matplotlib.image import imread

    fig = geometry_figures.plot_pair_pictures(geometry_dirs)
    assert_readable(fig)
    titles = [ax.get_title() for ax in fig.axes]
    assert titles[0].startswith("SBG: circular-arc") and titles[1].startswith("LSBG: logarithmic")
    assert all("spiral angle 35°" in t for t in titles)
    height = imread(Path(geometry_dirs["SBG"]) / "pair.png").shape[0]
    for ax in fig.axes:
        assert ax.images[0].get_array().shape[0] <= (1 - geometry_figures.PICTURE_CAPTION_SHARE) * height


def test_picture_crop_drops_the_caption_and_the_blank_border():
    image = np.ones((200, 300, 3))
    image[4:12, 100:200] = 0.0                     # caption text in the top 8 %
    yy, xx = np.mgrid[:200, :300]
    image[(yy - 110) ** 2 + (xx - 150) ** 2 < 50 ** 2] = 0.5   # the "gears"
    shown = geometry_figures._picture_without_caption(image, caption_share=0.08)
    assert not (shown == 0.0).any()                 # no caption left
    assert 100 <= shown.shape[0] <= 110 and 100 <= shown.shape[1] <= 110


@pytest.mark.parametrize("layout", [None, "constrained"])
def test_a_report_png_has_the_figures_pixels_in_a_palette(layout):
    """figure_png's palette image is the full-colour rendering, pixel for pixel, in at
    most 256 colours: the same bytes as quantizing matplotlib's own (compressed) PNG,
    so the uncompressed intermediate changes nothing but the time."""
    from PIL import Image

    fig = Figure(figsize=(8.0, 3.0), layout=layout)
    ax = fig.add_subplot()
    t = np.linspace(0.0, 1.0, 400)
    ax.plot(t, np.sin(40.0 * t), t, np.cos(9.0 * t))
    ax.fill_between(t, -1.0, np.sin(3.0 * t), alpha=0.3)
    ax.set_xlabel("time [s]")
    ax.set_ylabel("gear speed [deg/s]")
    full = figure_png(fig, palette=False)  # (also settles a constrained layout)
    shown = Image.open(io.BytesIO(figure_png(fig)))
    assert shown.mode == "P" and len(shown.getcolors(256)) <= 256
    rgb = np.asarray(Image.open(io.BytesIO(full)).convert("RGB"))
    reference = Image.fromarray(rgb).quantize(colors=256, method=Image.Quantize.FASTOCTREE,
                                              dither=Image.Dither.NONE)
    assert np.array_equal(np.asarray(shown.convert("RGB")), np.asarray(reference.convert("RGB")))
    out = io.BytesIO()
    reference.save(out, format="PNG")
    assert figure_png(fig) == out.getvalue()


def test_geometry_checks_read_well(geometry_dirs):
    assert_readable(geometry_figures.plot_spiral_angle_along_face(list(geometry_dirs.values())))
    errors = {label: point_checks.conjugacy_errors(read_design(path), phases=5, n=5)
              for label, path in geometry_dirs.items()}
    assert_readable(geometry_figures.plot_conjugacy(errors))


def test_pressure_angles_in_steps_of_the_double_resolution(geometry_dirs):
    table = verification_tables.pressure_angle_table(list(geometry_dirs.values()))
    ulp = np.spacing(20.0)
    table["design_deg"] = 20.0
    table["deviation_deg"] = ulp * np.array([1, 0, 1, 2, 1, -6, 1, 1])[:len(table)]
    fig = geometry_figures.plot_pressure_angles(table)
    assert_readable(fig)
    ax = fig.axes[0]
    assert ax.get_xscale() == "linear" and "[ulp" in ax.get_xlabel()
    shown = ax.collections[-1].get_offsets()[:, 0]
    np.testing.assert_allclose(shown, [1, 0, 1, 2, 1, -6, 1, 1][:len(table)])
    assert 0.0 in shown                           # a zero deviation is a point at 0
    assert "10⁻⁶ deg" in ax.get_title()           # the check's tolerance, stated


# -------------------------------------------------------------- time series
def test_time_series_read_well(point_runs):
    assert_readable(timeseries_figures.plot_time_series(point_runs, "pinion_speed", overlay=True))
    assert_readable(timeseries_figures.plot_time_series(point_runs, "gear_speed",
                                                        theory="gear_speed"))
    assert_readable(timeseries_figures.plot_steady_scatter(point_runs, "gear_speed", START))


def test_force_series_each_visible_with_the_legend_outside(point_runs):
    names = ["tangential_force", "tangential_force_outer"]
    fig = timeseries_figures.plot_time_series(point_runs, names, theory="tangential_force")
    assert_readable(fig)
    assert len(fig.axes) == 4                     # a row per force, a column per type
    for ax in fig.axes:
        series = [line for line in ax.lines if np.size(line.get_xdata()) > 2]
        assert len(series) == 1                   # nothing drawn over it but Eq. 13
    assert fig.legends and not any(ax.get_legend() for ax in fig.axes)
    shared = timeseries_figures.plot_time_series(point_runs, names, theory="tangential_force",
                                                 separate=False)
    assert_readable(shared)
    first, second = [line for line in shared.axes[0].lines if np.size(line.get_xdata()) > 2][:2]
    assert second.get_zorder() > first.get_zorder() and second.get_alpha() < 1
    assert second.get_linewidth() < first.get_linewidth()


# --------------------------------------------------------------- statistics
def test_statistics_charts_read_well(point_runs):
    for name in ("gear_speed", "tangential_force"):
        assert_readable(statistics_figures.plot_normality(point_runs, name, START))
        series = {label: ds[name].values[ds["time"].values > START]
                  for label, ds in point_runs.items()}
        units = point_runs["SBG"][name].attrs["units"]
        assert_readable(statistics_figures.plot_histogram(series, label=name, units=units))
    assert_readable(statistics_figures.plot_boxplots(point_runs, start=START))
    charts = paper_tables.control_charts(point_runs, "gear_speed", (START, 0.05), 5)
    for fig in statistics_figures.plot_control_charts(charts, label="gear angular velocity",
                                                      units="deg/s"):
        assert_readable(fig)


def test_histogram_folds_a_small_density_scale_into_the_unit():
    rng = np.random.default_rng(3)
    fig = statistics_figures.plot_histogram({"SBG": rng.normal(25000, 5000, 400)},
                                            label="tangential contact force", units="N")
    assert_readable(fig)
    assert fig.axes[0].get_ylabel() == "density [10⁻⁵/N]"
    assert not fig.axes[0].yaxis.get_offset_text().get_text()


# ------------------------------------------------------------------ spectra
def test_full_rate_figures_read_well(point_runs, line_runs):
    assert_readable(spectra_figures.plot_spectra(point_runs, "gear_speed", START,
                                                 title="point model"))
    assert_readable(spectra_figures.plot_spectra(line_runs, "transmission_error", START))
    fig = spectra_figures.plot_full_rate(line_runs, "gear_speed", start=START, span=0.01)
    assert_readable(fig)
    assert all(" ".join(ax.get_ylabel().split()) == "gear angular velocity [deg/s]"
               for ax in fig.axes)


def test_sampling_luck_labels_fit(point_runs, line_runs):
    luck_runs = {f"{t} {m}": ds for m, chosen in (("point", point_runs), ("line", line_runs))
                 for t, ds in chosen.items()}
    fig = spectra_figures.plot_sampling_luck(line_tables.sampling_luck_table(luck_runs, START))
    assert_readable(fig)
    assert {ax.get_title() for ax in fig.axes} == {"gear angular velocity",
                                                   "tangential contact force"}


# --------------------------------------------------------------------- mesh
def _points_per_cycle(line):
    x = np.asarray(line.get_xdata(), dtype=float)
    return (x.size - 1) / (x.max() - x.min()), x.max() - x.min()


def test_transmission_error_drawn_from_every_phase_over_two_cycles(meshes):
    fig = mesh_figures.plot_transmission_error(meshes)
    assert_readable(fig)
    phases = meshes["SBG"].sizes["mesh_phase"]
    curves = [line for ax in fig.axes for line in ax.lines if np.size(line.get_xdata()) > 2]
    assert len(curves) == 4
    for line in curves:
        density, span = _points_per_cycle(line)
        assert span == pytest.approx(2.0) and density >= 32 and density == pytest.approx(phases)
    for ax in fig.axes:
        assert "µ" in ax.get_ylabel() and "u" not in ax.get_ylabel().split("[")[1]


def test_transmission_error_refuses_a_coarse_analysis(meshes):
    coarse = {label: ds.isel(mesh_phase=slice(None, None, 4)) for label, ds in meshes.items()}
    assert coarse["SBG"].sizes["mesh_phase"] == 16
    with pytest.raises(ValueError, match="16 phases per mesh cycle.*at least 32"):
        mesh_figures.plot_transmission_error(coarse)


def test_load_sharing_and_contact_pattern_read_well(meshes):
    assert_readable(mesh_figures.plot_load_sharing(meshes))
    assert_readable(mesh_figures.plot_contact_pattern(meshes))


# ------------------------------------------------------------------- trends
def test_sweep_figures_read_well(sweep_table):
    assert_readable(trend_figures.plot_mesh_trends(sweep_table[sweep_table.contact_model == "line"]))
    fig = trend_figures.plot_fluctuation_trends(sweep_table)
    assert_readable(fig)
    line, point = fig.axes[:2]
    assert line.get_ylabel() == point.get_ylabel() == "std of the gear angular velocity [deg/s]"
    assert "line model" in line.get_title() and "full-rate" in line.get_title()
    assert "point model" in point.get_title() and "500 samples" in point.get_title()
    ratios = pd.DataFrame([{"quantity": q, "spiral_angle_deg": a, "ratio": 0.9,
                            "ratio_low": 0.85, "ratio_high": 0.95}
                           for q in ("gear_speed", "tangential_force") for a in _angles()])
    assert_readable(trend_figures.plot_ratio_trends(ratios))


def test_sensitivity_cells_do_not_overprint():
    cells = ["line model (baseline)", "point model", "line stiffness ×0.5", "line stiffness ×2",
             "damping ratio ×0.5", "damping ratio ×2", "slices ×2", "500-Hz sampling"]
    table = pd.DataFrame([{"cell": c, "quantity": q, "ratio": 0.85, "ratio_low": 0.8,
                           "ratio_high": 0.9, "holds": k % 2 == 0}
                          for k, c in enumerate(cells) for q in ("gear_speed", "tangential_force")])
    assert_readable(trend_figures.plot_sensitivity(table))


def test_speed_figures_read_well(speed_curve):
    assert_readable(speed_figures.plot_speed_curve(speed_curve))
    assert_readable(speed_figures.plot_campbell(speed_curve))


# ------------------------------------------------------------- verification
def test_convergence_reads_well():
    rows = []
    for engine, values, default in (("pybullet", (1e-6, 2e-6, 4e-6), 1e-6),
                                    ("scipy", (1e-10, 1e-8, 1e-6), 1e-8),
                                    ("compiled", (1e-10, 1e-8, 1e-6), 1e-8)):
        for trace in ("circular", "logarithmic"):
            for k, value in enumerate(values):
                rows.append({"engine": engine, "trace": trace, "value": value,
                             "is_default": value == default,
                             "gear_speed_std_deg_s": 25.0 + k, "tangential_force_std_N": 5000 + k,
                             "gear_speed_std_rel_diff_percent": 0.1 * k,
                             "tangential_force_std_rel_diff_percent": 0.2 * k})
    assert_readable(verification_figures.plot_convergence(pd.DataFrame(rows)))


def test_engine_agreement_twelve_labels_do_not_overlap(agreement):
    assert len(agreement) == 12
    fig = verification_figures.plot_engine_agreement(agreement)
    assert_readable(fig)
    ax = fig.axes[0]
    labels = _drawn_tick_labels(ax.yaxis)
    assert len(labels) == 12 and len({t.get_text() for t in labels}) == 12
    assert not _overlapping(labels, fig.canvas.get_renderer())
    assert ax.get_xlabel() == "std(engine) / std(reference engine) [-]"
