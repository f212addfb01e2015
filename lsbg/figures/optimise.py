"""Figures of each type's ease-off optimisation (:mod:`lsbg.optimise`)."""

from __future__ import annotations

from matplotlib.ticker import MaxNLocator

from lsbg.figures.base import axis_label, figure_legend, new_figure, type_color, wrap_label

__all__ = ["plot_fronts", "plot_hypervolume", "plot_eaf_difference"]

#: The fronts' panels: (x objective, y objective).
FRONT_PANELS = (("transmission_error", "contact_pressure"),
                ("transmission_error", "pattern_movement"),
                ("transmission_error", "mesh_loss"))


def _label(ds, name):
    return axis_label(ds[name].attrs.get("long_name", name.replace("_", " ")),
                      ds[name].attrs.get("units", ""), wrap=30)


def plot_fronts(fronts, releases=None):
    """Each type's Pareto front on common axes, both seeds, the released, the alternatives
    and the shared design; and the verdict: the FE figures of the candidates.

    Parameters
    ----------
    fronts : dict
        ``{(gear type, seed): front dataset}``
        (:func:`lsbg.optimise.dataset.front_dataset`).
    releases : dict, optional
        ``{gear type: release dataset}`` (:func:`lsbg.optimise.release.release_dataset`).

    Returns
    -------
    matplotlib.figure.Figure
        Three panels of the loaded TE over the load range [µrad] against the
        contact pressure [MPa], the pattern's movement over the envelope [mm]
        and the mesh loss [%] at the search's positions: the front's members
        (filled: the study's seed, open: the other seeds), the candidates evaluated
        under FE (diamonds: the alternatives), the released design (star) and
        the shared ease-off (a cross: it need not meet the constraints), one
        colour per type. With ``releases``, a fourth: the FE loaded TE over the
        load range against the FE peak pressure of the shared design (cross)
        and the candidates at converged positions (filled: released), with the
        release's limits (the shared design's values plus the tolerance, dashed).
    """
    panels_count = len(FRONT_PANELS) + (1 if releases else 0)
    fig, axes = new_figure(1, panels_count, width=4.4, height=3.4)
    panels = axes.ravel()
    seeds = sorted({seed for _, seed in fronts})
    releases = releases or {}
    for (kind, seed), ds in fronts.items():
        color = type_color(kind)
        on_front = ds["front"].values.astype(bool)
        first = seed == seeds[0]
        release = releases.get(kind)
        for ax, (x, y) in zip(panels, FRONT_PANELS):
            if x not in ds or y not in ds:
                continue
            ax.plot(ds[x].values[on_front], ds[y].values[on_front], "o", ms=4,
                    color=color, mfc=color if first else "none", lw=0, alpha=0.6,
                    label=f"{kind}, front of seed {seed}")
            if release is not None:
                mine = (release["front_seed"].values == seed) & (
                    release["fe_evaluated"].values == 1)
                members = release["individual"].values[mine]
                ax.plot(ds[x].values[members], ds[y].values[members], "D", ms=6, color=color,
                        mec="k", mew=0.6, lw=0,
                        label=f"{kind}, evaluated under FE" if first else None)
                k = int(release.attrs["chosen"])
                if k >= 0 and int(release["front_seed"].values[k]) == seed:
                    i = int(release["individual"].values[k])
                    ax.plot(ds[x].values[i], ds[y].values[i], "*", ms=14, color=color,
                            mec="k", mew=0.6, label=f"{kind}, released")
            if first:
                ax.plot(float(ds[f"reference_{x}"]), float(ds[f"reference_{y}"]), "x",
                        ms=9, mew=2, color=color, label=f"{kind}, shared ease-off")
    some = next(iter(fronts.values()))
    for ax, (x, y) in zip(panels, FRONT_PANELS):
        if x in some and y in some:
            ax.set_xlabel(_label(some, x) + " (search)")
            ax.set_ylabel(_label(some, y))
        ax.grid(True, alpha=0.3)
    if releases:
        _plot_verdict(panels[-1], releases)
    figure_legend(fig, [panels[0], panels[-1]] if releases else [panels[0]], ncols=4)
    return fig


def _plot_verdict(ax, releases):
    """The FE panel: TE over the load range against the peak pressure, the release's limits."""
    for kind, ds in releases.items():
        color = type_color(kind)
        x, y = "fe_peak_contact_pressure", "fe_transmission_error"
        evaluated = ds["fe_evaluated"].values == 1
        released = ds["released"].values == 1
        ax.plot(ds[x].values[evaluated & ~released], ds[y].values[evaluated & ~released], "D",
                ms=6, color=color, mfc="none", lw=0, label=f"{kind}, not released (FE)")
        if released.any():
            ax.plot(ds[x].values[released], ds[y].values[released], "D", ms=6, color=color,
                    lw=0, label=f"{kind}, released (FE)")
        k = int(ds.attrs["chosen"])
        if k >= 0:
            ax.plot(ds[x].values[k], ds[y].values[k], "*", ms=14, color=color, mec="k",
                    mew=0.6)
        px, py = float(ds[f"reference_{x}"]), float(ds[f"reference_{y}"])
        ax.plot(px, py, "x", ms=9, mew=2, color=color)
        tolerance = float(ds.attrs["release_tolerance"])
        # the release's limits: below both lines (and the root stress's) is no worse
        ax.axvline(px * (1 + tolerance), color=color, ls="--", lw=1)
        ax.axhline(py * (1 + tolerance), color=color, ls="--", lw=1)
    ax.set_xlabel(axis_label("largest Hertz pressure, edges included, over the load range "
                             "and the envelope (FE)", "MPa", wrap=30))
    ax.set_ylabel(axis_label("loaded TE over the load range, aligned (FE)", "µrad", wrap=30))
    ax.grid(True, alpha=0.3)


def plot_hypervolume(fronts):
    """The hypervolume of each search against the generation: the convergence evidence.

    Parameters
    ----------
    fronts : dict
        ``{(gear type, seed): front dataset}``.

    Returns
    -------
    matplotlib.figure.Figure
        Hypervolume of the feasible front [-] (normalised objectives, the
        dataset's reference point) against the generation, one colour per type,
        solid the study's seed, dashed the others.
    """
    fig, axes = new_figure(1, 1, width=6.0, height=3.4)
    ax = axes[0][0]
    seeds = sorted({seed for _, seed in fronts})
    for (kind, seed), ds in fronts.items():
        ax.plot(ds["generation"].values, ds["hypervolume"].values,
                "-" if seed == seeds[0] else "--", color=type_color(kind), lw=1.4,
                marker=".", label=f"{kind}, seed {seed}")
    ax.set_xlabel("generation")
    ax.xaxis.set_major_locator(MaxNLocator(integer=True))  # generations are whole
    ax.set_ylabel("hypervolume of the feasible front [-]")
    ax.set_ylim(bottom=0)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize="small")
    return fig


def plot_eaf_difference(ds, projection="transmission_error / contact_pressure"):
    """The difference of the two traces' empirical attainment functions in one projection.

    Parameters
    ----------
    ds : xarray.Dataset
        :func:`lsbg.optimise.fronts.trace_fronts_dataset`.
    projection : str
        One of its ``projection`` labels (``x / y``); the first where it has not this one.

    Returns
    -------
    matplotlib.figure.Figure
        The normalised common box [0, reference point]^2 of the two objectives [-],
        each rectangle coloured by the share of the first trace's seeds attaining it
        less the second's [-] (red: the first trace's, blue: the second's), its
        statistic and permutation p in the title.
    """
    import numpy as np
    from matplotlib.collections import PatchCollection
    from matplotlib.patches import Rectangle

    labels = [str(p) for p in ds["projection"].values]
    k = labels.index(projection) if projection in labels else 0
    x_name, y_name = labels[k].split(" / ")
    from lsbg.gear.design import TRACE_LABELS

    traces = [TRACE_LABELS.get(str(t), str(t)) for t in ds["trace"].values]
    reference = float(ds.attrs["reference_point"])
    rectangles = ds["eaf_rectangle"].values[k]
    difference = ds["eaf_difference"].values[k]
    keep = np.isfinite(difference)
    fig, axes = new_figure(1, 1, width=6.4, height=4.6)
    ax = axes[0][0]
    patches = [Rectangle((r[0], r[1]), r[2] - r[0], r[3] - r[1]) for r in rectangles[keep]]
    collection = PatchCollection(patches, cmap="RdBu_r", edgecolor="none")
    collection.set_array(difference[keep])
    collection.set_clim(-1, 1)
    ax.add_collection(collection)
    bar = fig.colorbar(collection, ax=ax)
    bar.set_label(f"EAF difference, {traces[0]} less {traces[1]} [-]", fontsize="small")
    ax.set_xlim(0, reference)
    ax.set_ylim(0, reference)
    for axis, name, setter in ((0, x_name, ax.set_xlabel), (1, y_name, ax.set_ylabel)):
        low, high = float(ds[f"box_low_{name}"]), float(ds[f"box_high_{name}"])
        unit = ds[f"box_low_{name}"].attrs["units"].replace("urad", "µrad")
        setter(wrap_label(f"{name.replace('_', ' ')}, normalised: 0 = {low:.4g}, "
                          f"1 = {high:.4g} {unit} [-]", 44))
    ax.set_title(f"mean |difference| {float(ds['eaf_difference_statistic'].values[k]):.3g}, "
                 f"permutation p {float(ds['eaf_difference_p'].values[k]):.2g} "
                 f"({int(ds.attrs['labelings'])} labelings)", fontsize="small")
    ax.grid(True, alpha=0.3)
    return fig
