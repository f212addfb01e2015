"""Figures of each type's ease-off optimisation (:mod:`lsbg.optimise`)."""

from __future__ import annotations

from matplotlib.ticker import MaxNLocator

from lsbg.figures.base import axis_label, figure_legend, new_figure, type_color

__all__ = ["plot_fronts", "plot_hypervolume"]

#: The fronts' panels: (x objective, y objective).
FRONT_PANELS = (("transmission_error", "contact_pressure"),
                ("transmission_error", "pattern_movement"),
                ("transmission_error", "mesh_loss"))


def _label(ds, name):
    return axis_label(ds[name].attrs.get("long_name", name.replace("_", " ")),
                      ds[name].attrs.get("units", ""), wrap=30)


def plot_fronts(fronts):
    """Each type's Pareto front on common axes, both seeds, the chosen and the shared design.

    Parameters
    ----------
    fronts : dict
        ``{(gear type, seed): front dataset}``
        (:func:`lsbg.optimise.dataset.front_dataset`).

    Returns
    -------
    matplotlib.figure.Figure
        Three panels of the loaded TE over the load range [µrad] against the
        contact pressure [MPa], the pattern's movement over the envelope [mm]
        and the mesh loss [%]: the front's members (filled: the study's seed,
        open: the next), the chosen design (star) and the shared ease-off (a
        cross: it need not meet the constraints), one colour per type.
    """
    fig, axes = new_figure(1, len(FRONT_PANELS), width=4.4, height=3.4)
    panels = axes.ravel()
    seeds = sorted({seed for _, seed in fronts})
    for (kind, seed), ds in fronts.items():
        color = type_color(kind)
        on_front = ds["front"].values.astype(bool)
        first = seed == seeds[0]
        for ax, (x, y) in zip(panels, FRONT_PANELS):
            if x not in ds or y not in ds:
                continue
            ax.plot(ds[x].values[on_front], ds[y].values[on_front], "o", ms=4,
                    color=color, mfc=color if first else "none", lw=0,
                    label=f"{kind}, front of seed {seed}")
            if first:
                chosen = int(ds.attrs["chosen"])
                if chosen >= 0:
                    ax.plot(ds[x].values[chosen], ds[y].values[chosen], "*", ms=13,
                            color=color, mec="k", mew=0.6, label=f"{kind}, chosen")
                ax.plot(float(ds[f"reference_{x}"]), float(ds[f"reference_{y}"]), "x",
                        ms=9, mew=2, color=color, label=f"{kind}, shared ease-off")
    some = next(iter(fronts.values()))
    for ax, (x, y) in zip(panels, FRONT_PANELS):
        if x in some and y in some:
            ax.set_xlabel(_label(some, x))
            ax.set_ylabel(_label(some, y))
        ax.grid(True, alpha=0.3)
    figure_legend(fig, [panels[0]], ncols=3)
    return fig


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
        solid the study's seed, dashed the next.
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
