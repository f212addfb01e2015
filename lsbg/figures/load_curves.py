"""Load curves: the FE loaded TCA and ISO 10300 against torque (:mod:`lsbg.practice.load_curve`)."""

from __future__ import annotations

from lsbg.figures.base import axis_label, figure_legend, new_figure, type_color

__all__ = ["DESIGN_STYLES", "plot_load_curves"]

#: Line style of each design: the pair as published, as a designer would make it.
DESIGN_STYLES = {"paper": ("--", "as published"), "practice": ("-", "as a designer would make it")}

#: The panels: (variable, words, unit, ISO's variable beside it or None).
PANELS = (
    ("transmission_error_peak_to_peak", "loaded TE peak to peak", "µrad", None),
    ("transmission_error_first_harmonic", "loaded TE, first mesh harmonic", "µrad", None),
    ("max_contact_pressure", "largest contact pressure", "MPa", "iso_contact_stress"),
    ("root_stress_pinion", "pinion root stress", "MPa", "iso_root_stress_pinion"),
    ("edge_load_share", "load at the profile's edges", "%", None),
    ("pattern_length", "loaded pattern length", "mm", None),
)


def _cycle_max(ds, name):
    values = ds[name]
    return values.max("mesh_phase") if "mesh_phase" in values.dims else values


def plot_load_curves(curves):
    """TE, pressure, root stress, edge load and pattern against torque, both designs.

    Parameters
    ----------
    curves : dict
        ``{(design set, gear type): load curve}``
        (:func:`lsbg.practice.load_curve.load_curve`), design set ``paper``
        or ``practice``.

    Returns
    -------
    matplotlib.figure.Figure
        Six panels against the gear torque [N m]: loaded TE peak to peak and
        first harmonic [µrad], the largest contact pressure [MPa] with ISO
        10300's sigma_H (dotted), the pinion's root stress [MPa] with ISO's
        sigma_F (dotted), the share of the load at the profile's edges [%]
        and the loaded pattern's length [mm]; one colour per type, solid the
        practice design, dashed the published pair; a grey tick at each
        design's rated pitting torque.
    """
    fig, axes = new_figure(2, 3, width=4.2, height=3.0)
    panels = axes.ravel()
    for (design_set, kind), ds in curves.items():
        style, words = DESIGN_STYLES[design_set]
        torque = ds["torque"].values
        color = type_color(kind)
        for ax, (name, _, unit, iso) in zip(panels, PANELS):
            values = _cycle_max(ds, name).values * (100.0 if unit == "%" else 1.0)
            ax.plot(torque, values, style, color=color, lw=1.2, marker=".", ms=4,
                    label=f"{kind}, {words}")
            if iso is not None:
                ax.plot(torque, ds[iso].values, ":", color=color, lw=1.0)
            ax.axvline(float(ds.attrs["rated_torque_pitting_N_m"]), color="0.6", lw=0.6,
                       ls=style)
    for ax, (_, words, unit, iso) in zip(panels, PANELS):
        label = words + (" (dotted: ISO 10300)" if iso else "")
        ax.set_ylabel(axis_label(label, unit, wrap=28))
        ax.set_xlabel("gear torque [N·m]")
        ax.grid(True, alpha=0.3)
    figure_legend(fig, [panels[0]], ncols=2)
    return fig
