"""Figures of the loaded tooth contact analysis (:mod:`lsbg.ltca`)."""

from __future__ import annotations

import numpy as np

from lsbg.figures.base import new_figure, type_color


def plot_transmission_error(meshes):
    """Loaded static transmission error and mesh stiffness over one mesh cycle.

    Parameters
    ----------
    meshes : dict
        ``{gear type: loaded-TCA dataset}``.

    Returns
    -------
    matplotlib.figure.Figure
        Left: transmission error [urad]; right: mesh stiffness [N/um], both
        against the mesh phase (fraction of a base pitch), one line per type.
    """
    fig, axes = new_figure(1, 2, width=4.4)
    te, stiffness = axes[0]
    for label, ds in meshes.items():
        phase = ds["mesh_phase"].values
        color = type_color(label)
        te.plot(phase, ds["transmission_error"].values, color=color,
                label=f"{label}: {ds.attrs['transmission_error_peak_to_peak_urad']:.4g} urad p-p")
        stiffness.plot(phase, ds["mesh_stiffness"].values, color=color,
                       label=f"{label}: mean {ds.attrs['mesh_stiffness_mean_N_per_um']:.4g} N/um, "
                             f"{ds.attrs['mesh_stiffness_variation_percent']:.3g} % p-p")
    te.set_ylabel("loaded static transmission error [urad]")
    stiffness.set_ylabel("mesh stiffness along the line of action [N/um]")
    for ax in (te, stiffness):
        ax.set_xlabel("mesh phase [base pitches]")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize="small")
    return fig


def plot_load_sharing(meshes):
    """Normal load of one tooth pair on its way through the field of contact.

    Parameters
    ----------
    meshes : dict
        ``{gear type: loaded-TCA dataset}``.

    Returns
    -------
    matplotlib.figure.Figure
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
    ax.legend(fontsize="small", markerscale=4)
    return fig


def plot_contact_pattern(meshes):
    """Load per unit length over the flank (face width x profile), per gear type.

    Parameters
    ----------
    meshes : dict
        ``{gear type: loaded-TCA dataset}``.

    Returns
    -------
    matplotlib.figure.Figure
        One panel per type with a shared colour scale [N/mm].
    """
    fig, axes = new_figure(1, len(meshes), width=4.2, height=3.4)
    top = max(float(ds["contact_pattern"].max()) for ds in meshes.values())
    image = None
    for ax, (label, ds) in zip(axes[0], meshes.items()):
        pattern = ds["contact_pattern"].values
        image = ax.pcolormesh(ds["profile_angle"].values, ds["cone_distance"].values,
                              np.ma.masked_less_equal(pattern, 0.0), vmin=0.0, vmax=top,
                              shading="auto", cmap="viridis")
        ax.set_title(label)
        ax.set_xlabel("path of contact [deg in the plane of action]")
        ax.set_ylabel("cone distance [mm]")
    if image is not None:
        fig.colorbar(image, ax=list(axes[0]), label="load per unit length [N/mm]")
    return fig
