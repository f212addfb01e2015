"""Figures of the loaded tooth contact analysis (:mod:`lsbg.tca.loaded`)."""

from __future__ import annotations

import numpy as np

from lsbg.figures.base import axis_label, figure_legend, flank_maps, new_figure, type_color


#: Fewest mesh phases per cycle the transmission-error figure accepts [-]. The
#: curves are piecewise linear with a few kinks per cycle; a coarse grid puts
#: its points beside the kinks, cuts the peaks off, and draws what looks like
#: sampling rather than the curve (the default analysis has 256,
#: :data:`lsbg.tca.loaded.PHASES`).
MIN_PHASES = 32


def _periodic(phase, values, cycles):
    """A one-cycle series (endpoint excluded) repeated over ``cycles`` cycles and closed."""
    phase, values = np.asarray(phase, dtype=float), np.asarray(values, dtype=float)
    x = np.concatenate([phase + k for k in range(cycles)] + [[float(cycles)]])
    y = np.concatenate([values] * cycles + [values[:1]])
    return x, y


def _pair_changes(ds, cycles):
    """Mesh phases (over ``cycles``) at which the number of loaded tooth pairs changes."""
    if "pair_load" not in ds:
        return np.array([])
    loaded = (ds["pair_load"].values > 0).sum(axis=1)
    phase = ds["mesh_phase"].values
    # between two phases, and across the cycle's end to the next cycle's start
    step = np.flatnonzero(np.diff(np.append(loaded, loaded[0])))
    spacing = 1.0 / loaded.size
    once = phase[step] + 0.5 * spacing
    return np.concatenate([once + k for k in range(cycles)])


def plot_transmission_error(meshes, cycles=2):
    """Loaded static transmission error and mesh stiffness over mesh cycles.

    Both curves are piecewise linear in the mesh phase: they bend where a
    tooth pair enters or leaves the field of contact (dotted verticals, where
    the number of loaded pairs changes) and where the end of a contact line
    passes a corner of the field (the contact length changes its slope).
    Every computed phase is drawn as a point, over ``cycles`` repetitions of
    the one cycle computed, so the straight stretches and sharp peaks read as
    the curve itself, not as coarse sampling.

    Parameters
    ----------
    meshes : dict
        ``{gear type: loaded-TCA dataset}``, each with at least
        :data:`MIN_PHASES` phases over one mesh cycle.
    cycles : int
        Mesh cycles drawn (the one computed, repeated) [-].

    Returns
    -------
    matplotlib.figure.Figure
        Left: transmission error [µrad]; right: mesh stiffness [N/µm], both
        against the mesh phase (base pitches), one line per type; the legend
        above with the peak-to-peak values.

    Raises
    ------
    ValueError
        If a dataset has fewer than :data:`MIN_PHASES` phases per mesh cycle.
    """
    for label, ds in meshes.items():
        phases = ds.sizes.get("mesh_phase", 0)
        if phases < MIN_PHASES:
            raise ValueError(f"{label}: the loaded TCA has {phases} phases per mesh cycle; the "
                             f"figure needs at least {MIN_PHASES} to resolve where tooth pairs "
                             f"enter and leave the field of contact (lsbg ltca --phases, "
                             f"default 256)")
    fig, axes = new_figure(1, 2, width=4.6)
    te, stiffness = axes[0]
    counts = set()
    for label, ds in meshes.items():
        phase = ds["mesh_phase"].values
        counts.add(phase.size)
        color = type_color(label)
        te.plot(*_periodic(phase, ds["transmission_error"].values, cycles), ".-", ms=2.5, lw=0.8,
                color=color,
                label=f"{label}: TE {ds.attrs['transmission_error_peak_to_peak_urad']:.4g} µrad "
                      f"p-p; stiffness mean {ds.attrs['mesh_stiffness_mean_N_per_um']:.4g} N/µm, "
                      f"{ds.attrs['mesh_stiffness_variation_percent']:.3g} % p-p")
        stiffness.plot(*_periodic(phase, ds["mesh_stiffness"].values, cycles), ".-", ms=2.5,
                       lw=0.8, color=color)
        for ax in (te, stiffness):
            for x in _pair_changes(ds, cycles):
                ax.axvline(x, color=color, ls=":", lw=0.8)
    te.plot([], [], color="0.3", ls=":", lw=0.8,
            label="a tooth pair enters or leaves the field of contact")
    te.set_ylabel(axis_label("loaded static transmission error", "urad", wrap=30))
    stiffness.set_ylabel(axis_label("mesh stiffness along the line of action", "N/um", wrap=30))
    count = ", ".join(str(n) for n in sorted(counts))
    for ax in (te, stiffness):
        ax.set_xlabel(f"mesh phase [base pitches] ({count} phases per pitch)")
        ax.set_xlim(0.0, float(cycles))
        ax.set_xticks(np.arange(0.0, cycles + 0.25, 0.5))
        ax.grid(True, alpha=0.3)
    figure_legend(fig, [te], ncols=1)
    return fig


def plot_load_sharing(meshes):
    """Normal load of one tooth pair on its way through the field of contact.

    Parameters
    ----------
    meshes : dict
        ``{gear type: loaded-TCA dataset}`` (:func:`lsbg.tca.loaded.loaded_tca`):
        its ``tooth_pair_load`` [N] over ``passage`` [base pitches].

    Returns
    -------
    matplotlib.figure.Figure
        One panel: the load [kN] against the position of the pair's contact
        line in the field [base pitches], one colour per type.
    """
    fig, axes = new_figure(1, 1, width=7.0)
    ax = axes[0, 0]
    for label, ds in meshes.items():
        passage = ds["passage"].values
        ax.plot(passage - passage.min(), ds["tooth_pair_load"].values * 1e-3, ".", ms=2,
                color=type_color(label), label=label)
    ax.set_xlabel("position of the tooth pair's contact line in the field [base pitches]")
    ax.set_ylabel("normal load of the tooth pair [kN]")
    ax.grid(True, alpha=0.3)
    figure_legend(fig, markerscale=4)
    return fig


def plot_contact_pattern(meshes):
    """Load per unit length over the flank (face width x profile), per gear type.

    Parameters
    ----------
    meshes : dict
        ``{gear type: loaded-TCA dataset}`` (:func:`lsbg.tca.loaded.loaded_tca`):
        its ``contact_pattern`` over (cone_distance, profile_angle) [N/mm].

    Returns
    -------
    matplotlib.figure.Figure
        One panel per type with a shared colour scale [N/mm].
    """
    return flank_maps(meshes, "contact_pattern", "profile_angle", "viridis",
                      "load per unit length [N/mm]")
