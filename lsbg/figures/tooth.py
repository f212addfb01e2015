"""Figures of the loaded TCA with the tooth's own compliance (:mod:`lsbg.tooth`)."""

from __future__ import annotations

from lsbg.figures.base import axis_label, figure_legend, flank_maps, new_figure, type_color

__all__ = ["plot_stresses", "plot_contact_pressure"]


def plot_stresses(fe_ltcas):
    """Root stress of pinion and gear and the largest contact pressure over the mesh cycle.

    Parameters
    ----------
    fe_ltcas : dict
        ``{gear type: loaded TCA with the FE compliance}``
        (:func:`lsbg.tooth.analysis.fe_ltca`).

    Returns
    -------
    matplotlib.figure.Figure
        Left: largest tensile principal stress in the root fillets [MPa]
        (pinion solid, gear dashed); right: largest Hertz pressure on the
        flanks [MPa]; both against the mesh phase, one colour per type.
    """
    fig, axes = new_figure(1, 2, width=4.6)
    root, pressure = axes[0]
    for label, ds in fe_ltcas.items():
        phase = ds["mesh_phase"].values
        color = type_color(label)
        root.plot(phase, ds["root_stress_pinion"].values, "-", color=color, lw=1.0,
                  label=f"{label}: pinion (max {ds.attrs['max_root_stress_pinion_MPa']:.4g} MPa), "
                        f"gear dashed (max {ds.attrs['max_root_stress_gear_MPa']:.4g} MPa)")
        root.plot(phase, ds["root_stress_gear"].values, "--", color=color, lw=1.0)
        pressure.plot(phase, ds["max_contact_pressure"].values, "-", color=color, lw=1.0)
    root.set_ylabel(axis_label("largest tensile principal stress in the root fillets", "MPa",
                               wrap=30))
    pressure.set_ylabel(axis_label("largest Hertz pressure on the flanks", "MPa", wrap=30))
    for ax in (root, pressure):
        ax.set_xlabel("mesh phase [base pitches]")
        ax.set_xlim(0.0, 1.0)
        ax.grid(True, alpha=0.3)
    figure_legend(fig, [root], ncols=1)
    return fig


def plot_contact_pressure(fe_ltcas):
    """The largest Hertz pressure met at each point of the flank over the cycle, per type.

    Parameters
    ----------
    fe_ltcas : dict
        ``{gear type: loaded TCA with the FE compliance}``
        (:func:`lsbg.tooth.analysis.fe_ltca`): its ``contact_pressure`` over
        (cone_distance, pressure_profile_angle) [MPa].

    Returns
    -------
    matplotlib.figure.Figure
        One panel per type (face width x path of contact), shared colour
        scale [MPa].
    """
    return flank_maps(fe_ltcas, "contact_pressure", "pressure_profile_angle", "magma",
                      "largest Hertz pressure [MPa]")
