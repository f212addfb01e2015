"""The pair as a designer would make it: ``lsbg practice`` and ``lsbg load-curve``.

``lsbg practice`` writes the practice design (:mod:`lsbg.practice.design`) as a
configuration overlay: the workflow's practice rules run the same commands as
the paper's point with ``--config results/config.yaml --config
results/practice/design.yaml``, so every setting the overlay does not name is
the study's.
"""

from __future__ import annotations

from lsbg.cli.options import (
    CommandError,
    add_config_options,
    add_geometry_input,
    add_output,
    checked,
    command_line,
    contact_of,
    design_of,
    fe_compliance_of,
    flanks_of,
)

__all__ = ["add_practice_parser", "add_load_curve_parser"]

#: The sections ``lsbg practice`` reads.
PRACTICE_SECTIONS = ("design", "practice", "rating", "tooth", "simulation", "flank_modification")


def add_practice_parser(subparsers):
    """``lsbg practice``: the practice design as a configuration overlay."""
    parser = subparsers.add_parser(
        "practice", help="the pair as a designer would make it, as a configuration overlay",
        description="Make the pair of the 'design' section as bevel practice makes it, by the "
                    "rules of the 'practice' section: the depth shares of its addendum_rule "
                    "(ISO 23509's mean addendum factor, or AGMA 209's) as ISO 23509's mean "
                    "profile shift x_hm1, the thickness modification x_smn1 that "
                    "balances the ISO 10300 root stresses, undercut refused, a linear tip "
                    "relief of both members as large as the mesh's deflection at its rated "
                    "torque (ISO 6336-1's mesh stiffness), and that torque as its load; write "
                    "the keys to --out (YAML), to be given as a second --config after the "
                    "study's.")
    add_config_options(parser, PRACTICE_SECTIONS)
    add_output(parser, metavar="OVERLAY.yaml", help="output YAML file")
    parser.set_defaults(handler=run_practice)


def run_practice(args):
    """Handler of ``lsbg practice``: its summary lines."""
    from lsbg.files import write_text_atomically
    from lsbg.gear.design import TRACE_NAMES
    from lsbg.practice.design import practice_overlay
    from lsbg.study.params import yaml_text

    overlay, figures = practice_overlay(design_of(args.settings), args.settings)
    comment = (f"the practice design (lsbg practice): x_hm1 {figures['profile_shift']:.6f} "
               f"by {figures['profile_shift_rule']}, "
               f"x_smn1 {figures['thickness_modification']:.6f}, rated gear torque "
               f"{figures['rated_torque_pitting_N_m']:.1f} N m (pitting), "
               f"{figures['rated_torque_bending_N_m']:.1f} N m (bending); the published "
               f"pair's {figures['published_rated_torque_pitting_N_m']:.1f} and "
               f"{figures['published_rated_torque_bending_N_m']:.1f} N m; its SBG: "
               f"{TRACE_NAMES[args.settings['practice']['sbg_trace']]}")
    text = yaml_text(overlay, comment)
    write_text_atomically(args.out, text)
    return [f"x_hm1 = {figures['profile_shift']:.4f} ({figures['profile_shift_rule']}), x_smn1 = "
            f"{figures['thickness_modification']:.4f}, rated torque "
            f"{figures['rated_torque_pitting_N_m']:.1f} N m (published pair "
            f"{figures['published_rated_torque_pitting_N_m']:.1f}), tip relief "
            f"{figures['tip_relief_um']:g} um over {figures['tip_relief_length']:g} of the "
            f"profile, load {figures['load_torque_N_m']:.1f} N m -> {args.out}"]


# ------------------------------------------------------------------ load-curve
#: The sections ``lsbg load-curve`` reads.
LOAD_CURVE_SECTIONS = ("practice", "rating", "tooth", "simulation", "contact",
                       "flank_modification", "misalignment")


def add_load_curve_parser(subparsers):
    """``lsbg load-curve``: the FE loaded TCA and ISO 10300 against torque."""
    parser = subparsers.add_parser(
        "load-curve", help="transmission error, pattern and stresses against torque",
        description="Run the loaded TCA with the tooth's FE compliance (--compliance-file, "
                    "computed there if missing) of the pair in --geometry at the torques "
                    "practice.load_range (fractions of the design's rated pitting torque by "
                    "ISO 10300) and --also-at, at practice.load_range_phases positions, and "
                    "write the transmission error (peak to peak, first harmonic), the loaded "
                    "pattern's length and width, the largest contact pressure (on the flank "
                    "and at its edges), the edge load and the root stresses against torque, "
                    "with ISO 10300's contact and root stresses at the same torques, to --out "
                    "(NetCDF).")
    add_geometry_input(parser)
    add_config_options(parser, LOAD_CURVE_SECTIONS)
    parser.add_argument("--compliance-file", required=True, metavar="COMPLIANCE.nc",
                        help="the design point's FE compliance (lsbg compliance): read if it "
                             "holds these inputs, else computed and written there")
    parser.add_argument("--also-at", dest="also_at", action="append", type=float, default=[],
                        metavar="N_M", help="another gear torque of the curve [N m], e.g. the "
                                            "paper's load; repeatable")
    parser.add_argument("--design-set", choices=("paper", "practice"), default="paper",
                        help="which design this is, recorded in --out (default: paper)")
    add_output(parser, metavar="CURVE.nc")
    parser.set_defaults(handler=run_load_curve)


def run_load_curve(args):
    """Handler of ``lsbg load-curve``: its summary lines."""
    import numpy as np

    from lsbg.contact import MeshContact
    from lsbg.files import write_dataset
    from lsbg.gear.geometry import GearPair
    from lsbg.practice.load_curve import load_curve
    from lsbg.solid.directory import read_design

    settings = args.settings
    flanks = flanks_of(settings)
    params = contact_of(settings, model="line")
    bad = [t for t in args.also_at if not t > 0]
    if bad:
        raise CommandError(f"--also-at {bad[0]!r}: must be a gear torque > 0 [N m]")
    compliance, _ = fe_compliance_of(args)
    pair = GearPair(read_design(args.geometry))
    contact = MeshContact(pair, params, separation=flanks.separation(pair))
    section = settings["practice"]
    ds = checked(lambda: load_curve(contact, compliance, settings, section["load_range"],
                                    args.also_at, section["load_range_phases"],
                                    args.design_set))
    ds.attrs["history"] = command_line()
    write_dataset(ds, args.out)
    rated = ds.attrs["rated_torque_pitting_N_m"]
    at = ds.sel(torque=ds["torque"].values[np.argmin(np.abs(ds["torque"].values - rated))])
    return [f"{ds.sizes['torque']} torques {ds['torque'].values[0]:.4g}-"
            f"{ds['torque'].values[-1]:.4g} N m; at the rated {rated:.4g} N m: largest "
            f"pressure {float(at['max_contact_pressure'].max()):.4g} MPa (ISO sigma_H "
            f"{float(at['iso_contact_stress']):.4g} MPa), TE "
            f"{float(at['transmission_error_peak_to_peak']):.3g} urad p-p -> {args.out}"]
