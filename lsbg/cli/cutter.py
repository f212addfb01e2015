"""The cutter-radius sweep on the command line: ``lsbg cutter-point``.

One point of the ``cutter_sweep`` section (:mod:`lsbg.experiments.cutter`): the pair of the
``design`` section (the workflow sets its trace, cutter radius and spiral angle) and its
quasi-static figures beside the LSBG's.
"""

from __future__ import annotations

from lsbg.cli.options import (CommandError, add_config_options, add_output, check_output,
                              checked, command_line, contact_of, design_of, flanks_of,
                              load_torque_of)

__all__ = ["add_cutter_point_parser"]

#: The sections a point reads.
SECTIONS = ("design", "simulation", "contact", "flank_modification", "misalignment", "tca",
            "misalignment_map", "tooth")


def add_cutter_point_parser(subparsers):
    """``lsbg cutter-point``: one point of the cutter-radius sweep."""
    parser = subparsers.add_parser(
        "cutter-point", help="one point of the cutter-radius sweep (quasi-static)",
        description="Build the pair of the 'design' section (in memory; its trace and "
                    "cutter_radius_mm set the point) and write its V-H map at "
                    "misalignment_map.sweep_steps to --out (NetCDF) with, as attributes "
                    "cutter_*, the loaded TE of the line model on the uniform bed at "
                    "simulation.load_torque_N_m and tca.loaded_positions, the FE loaded "
                    "TCA's largest contact pressure and root stresses (--fe; or read from "
                    "--fe-ltca), the pitch-cone trace's radius of curvature at the mean point "
                    "and the spiral angle at toe and heel.")
    add_config_options(parser, SECTIONS)
    parser.add_argument("--roles", nargs="+", required=True,
                        choices=("lsbg", "design", "nominal", "matched"),
                        help="what the point is in the sweep (recorded)")
    parser.add_argument("--radius-mm", type=float, required=True,
                        help="the point's cutter radius as the sweep names it [mm] (the "
                             "LSBG's: its R_m / sin beta_m; recorded)")
    fe = parser.add_mutually_exclusive_group()
    fe.add_argument("--fe", action="store_true",
                    help="compute the FE compliance (tooth section) and the FE loaded TCA")
    fe.add_argument("--fe-ltca", metavar="LTCA.nc",
                    help="the point's FE loaded TCA, already computed (lsbg ltca under "
                         "contact.compliance: fe, at the same design, flanks and load)")
    add_output(parser, metavar="POINT.nc", required=True)
    parser.set_defaults(handler=run_cutter_point)


def run_cutter_point(args):
    """Handler of ``lsbg cutter-point``: its summary line."""
    from lsbg.experiments.cutter import point_dataset
    from lsbg.files import open_dataset, write_dataset
    from lsbg.gear.geometry import GearPair

    check_output(args.out, "--out")
    design = design_of(args.settings)
    if design.trace != "logarithmic" and abs(design.cutter_radius * 1e3 - args.radius_mm) > 1e-6:
        raise CommandError(f"--radius-mm {args.radius_mm:g}: the design's cutter radius is "
                           f"{design.cutter_radius * 1e3:g} mm (set design.cutter_radius_mm)")
    pair = checked(lambda: GearPair(design))
    fe = "compute" if args.fe else None
    if args.fe_ltca:
        names = ("max_contact_pressure", "root_stress_pinion", "root_stress_gear")
        fe = open_dataset(args.fe_ltca, "FE loaded TCA", names, (), "an FE loaded TCA")
    ds = checked(lambda: point_dataset(pair, load_torque_of(args.settings),
                                       contact_of(args.settings, model="line"),
                                       flanks_of(args.settings), args.settings, fe))
    ds.attrs.update({"history": command_line(), "cutter_trace": design.trace,
                     "cutter_radius_mm": float(args.radius_mm),
                     "cutter_roles": " ".join(args.roles)})
    write_dataset(ds, args.out)
    a = ds.attrs
    return (f"{design.trace}, r_c {args.radius_mm:g} mm ({' '.join(args.roles)}): trace "
            f"curvature radius {a['cutter_trace_curvature_radius']:.4g} mm, loaded TE "
            f"{a['cutter_loaded_te_peak_to_peak']:.4g} urad, FE contact pressure "
            f"{a['cutter_max_contact_pressure']:.4g} MPa -> {args.out}")
