"""What the reports show that lsbg computes for them: ``lsbg checks``, ``lsbg rate-sweep``.

A report notebook only reads files and tabulates them (docs/architecture.md);
what it shows that takes a computation of lsbg's stages is a command's file:
the verification checks and the contact resonance of a design point
(:mod:`lsbg.experiments.point_checks`), and the ISO 10300 rating of every
design point of the sweep (:mod:`lsbg.experiments.rating_sweep`).
"""

from __future__ import annotations

from lsbg.cli.options import (CommandError, add_config_options, add_engine_option,
                              add_geometry_input, add_output, checked, command_line)

__all__ = ["add_checks_parser", "add_rate_sweep_parser"]


def add_checks_parser(subparsers):
    """``lsbg checks``: the verification checks of one design point."""
    parser = subparsers.add_parser(
        "checks", help="verification checks and contact resonance of one design point",
        description="Check at the design point of --geometry what nobody tuned: the flanks' "
                    "conjugacy (distance from the contact lines), the line model's loaded TCA "
                    "without load, at twice the load and with two and four times the slices "
                    "(the line model and load of --mesh), the tooth contact analysis from the "
                    "surfaces on the conjugate, the crowned (--mesh's crowning) and a displaced "
                    "pair, and the gear's torsional resonance on the point model's linearised "
                    "contact (the contact law and load of --run), with what their bounds need "
                    "(the surface TCA on a coarser grid and at half the crowning, the slices' "
                    "and the mesh phases' errors of --mesh's stiffness); write them to --out "
                    "(NetCDF) for the verification and paper reports.")
    add_geometry_input(parser)
    parser.add_argument("--mesh", required=True, metavar="MESH.nc",
                        help="the design point's loaded TCA (lsbg ltca)")
    parser.add_argument("--run", required=True, metavar="RUN.nc",
                        help="the design point's point-model run (lsbg simulate) whose contact "
                             "law and load the resonance takes")
    add_output(parser, metavar="CHECKS.nc")
    parser.set_defaults(handler=run_checks)


def run_checks(args):
    """Handler of ``lsbg checks``: its summary line."""
    from lsbg.dynamics.dataset import open_run
    from lsbg.experiments.point_checks import design_point_checks
    from lsbg.files import open_dataset, write_dataset
    from lsbg.solid.directory import read_design

    design = read_design(args.geometry)
    mesh = open_dataset(args.mesh, "mesh", ("transmission_error",),
                        ("load_torque_N_m", "contact_slices"), "a loaded-TCA dataset (lsbg ltca)")
    run = open_run(args.run)
    for option, ds in (("--mesh", mesh), ("--run", run)):
        difference = design.attrs_difference(ds.attrs)
        if difference is not None:
            key, stored, value = difference
            raise CommandError(f"{option} {ds.encoding['source']}: design {key} = {stored!r}, "
                               f"the geometry's {value!r}")
    if run.attrs.get("contact_model") != "point":
        raise CommandError(f"--run {args.run}: a {run.attrs.get('contact_model')}-model run; "
                           f"the resonance is the point model's")
    ds = design_point_checks(args.geometry, mesh, run, command_line())
    write_dataset(ds, args.out)
    worst = max(float(ds.conjugacy_pinion_distance.max()), float(ds.conjugacy_gear_distance.max()))
    return (f"conjugacy {worst:.2g} m, unloaded TE {float(ds.unloaded_te_max):.2g} rad, "
            f"crowned TE {float(ds.crowned_te_pp):.4g} urad "
            f"(closed form {float(ds.designed_te_pp):.4g}), resonance "
            f"{float(ds.resonance_frequency):.5g} Hz -> {args.out}")


def add_rate_sweep_parser(subparsers):
    """``lsbg rate-sweep``: ISO 10300 at every design point of the summary table."""
    parser = subparsers.add_parser(
        "rate-sweep", help="ISO 10300 rating of every design point of the sweep",
        description="Rate every design point of --summary (lsbg summary) by ISO 10300:2023 "
                    "method B1 at the study's load and speed with the 'rating' and 'tooth' "
                    "sections, K_v from the point's line-model run of --engine (the summary's "
                    "dynamic factor; 1 where it has none), and write the stresses, safety "
                    "factors and the rated gear torque per design point to --out (NetCDF).")
    add_config_options(parser, ("design", "rating", "tooth", "simulation"))
    parser.add_argument("--summary", required=True, metavar="SUMMARY.csv",
                        help="the study's summary table (lsbg summary)")
    add_engine_option(parser, default="compiled")
    add_output(parser, metavar="RATING.nc")
    parser.set_defaults(handler=run_rate_sweep)


#: Columns of the summary table that ``lsbg rate-sweep`` reads.
SUMMARY_COLUMNS = ("trace", "spiral_angle_deg", "contact_model", "engine", "dynamic_factor")


def run_rate_sweep(args):
    """Handler of ``lsbg rate-sweep``: its summary line."""
    import pandas as pd

    from lsbg.experiments.rating_sweep import rating_by_angle, rating_sweep_dataset
    from lsbg.files import InputError, write_dataset

    try:
        summary = pd.read_csv(args.summary)
    except FileNotFoundError:
        raise InputError(f"{args.summary}: no such summary table") from None
    except (OSError, ValueError) as err:
        raise InputError(f"{args.summary}: not a readable CSV table ({err})") from None
    missing = [c for c in SUMMARY_COLUMNS if c not in summary.columns]
    if missing:
        raise InputError(f"{args.summary}: not a summary table of lsbg summary (missing "
                         f"columns {missing})")
    table = checked(lambda: rating_by_angle(args.settings, summary, args.engine))
    load = float(args.settings["simulation"]["load_torque_N_m"])
    write_dataset(rating_sweep_dataset(table, args.engine, load, command_line()), args.out)
    return (f"{len(table)} design points rated, sigma_H {table.contact_stress.min():.0f}-"
            f"{table.contact_stress.max():.0f} MPa -> {args.out}" if len(table) else
            f"no design point in {args.summary} -> {args.out}")
