"""``lsbg rate``: a design point's ISO 10300 rating beside its FE stresses."""

from __future__ import annotations

import math

from lsbg.cli.options import (CommandError, add_config_options, add_geometry_input, add_output,
                              checked, parse_pairs)

__all__ = ["add_rate_parser"]


def add_rate_parser(subparsers):
    """``lsbg rate``: ISO 10300 method B1 of one design point."""
    parser = subparsers.add_parser(
        "rate", help="ISO 10300 rating of one design point (stresses, safety, rated torque)",
        description="Rate the pair in --geometry by ISO 10300:2023 method B1 (contact and "
                    "root stress of both members, permissible stresses, safety factors, the "
                    "gear torques at which they reach 1) at the study's load and speed "
                    "(the 'simulation' section) with the factors of the 'rating' "
                    "section, and write them to --out (NetCDF) beside the largest contact "
                    "pressure and root stresses of --fe-ltca (the FE loaded TCA).")
    add_geometry_input(parser)
    add_config_options(parser, ("rating", "tooth", "simulation", "statistics"))
    parser.add_argument("--run", metavar="RUN.nc",
                        help="the design point's line-model run: its dynamic factor is K_v "
                             "where rating.dynamic_factor is 'lsbg' (without it, K_v = 1)")
    parser.add_argument("--fe-ltca", metavar="LTCA.nc",
                        help="the design point's loaded TCA with the FE compliance (lsbg ltca "
                             "--set contact.compliance=fe) at the same load")
    parser.add_argument("--fe-envelope", metavar="ENVELOPE.nc",
                        help="the FE loaded TCA at the corners of the assembly's displacement "
                             "envelope (lsbg ltca --set contact.compliance=fe --envelope) at the same load")
    parser.add_argument("--case-run", action="append", default=[], metavar="CASE=RUN.nc",
                        help="a sensitivity case's line-model run (lsbg sensitivity) of the same "
                             "design point: the pair is rated again with its dynamic factor as "
                             "K_v (where rating.dynamic_factor is 'lsbg'); repeatable")
    add_output(parser, metavar="RATING.nc")
    parser.set_defaults(handler=run_rate)


def run_rate(args):
    """Handler of ``lsbg rate``: its summary line."""
    from lsbg.solid.directory import read_design
    from lsbg.rating.config import rate_design
    from lsbg.rating.dataset import rating_dataset
    from lsbg.files import open_dataset, write_dataset
    from lsbg.dynamics.dataset import open_run
    from lsbg.aggregate.summary import statistics_options

    rating, tooth, simulation = (args.settings[s] for s in ("rating", "tooth", "simulation"))
    design = read_design(args.geometry)
    after = checked(lambda: statistics_options(args.settings["statistics"]))["steady_state_after"]
    by_run = rating["dynamic_factor"] == "lsbg"
    kv, source = None, "K_v = 1: no run given"
    if by_run and args.run:
        run = _same_point(open_run(args.run), design, None, "--run")
        kv, source = _dynamic_factor(run, after, "--run"), f"the run {args.run}"
    elif not by_run:
        source = "rating.dynamic_factor"
    case_factors = {}
    for name, path in parse_pairs(args.case_run, "--case-run").items():
        if by_run:
            run = _same_point(open_run(path), design, None, "--case-run")
            case_factors[name] = _dynamic_factor(run, after, "--case-run")
    load = float(simulation["load_torque_N_m"])
    speed = math.radians(float(simulation["pinion_speed_deg_s"]))

    def rated(dynamic_factor):
        try:
            return rate_design(design, rating, tooth, load, speed, dynamic_factor)
        except ValueError as err:
            raise CommandError(f"{args.geometry}: {err}" if not str(err).startswith(
                ("rating.", "tooth.")) else str(err)) from None

    result, material, conditions = rated(kv)
    cases = {name: rated(factor)[0] for name, factor in case_factors.items()}
    fe = None
    if args.fe_ltca:
        fe = open_dataset(args.fe_ltca, "FE loaded TCA", ("max_contact_pressure",
                                                          "root_stress_pinion",
                                                          "root_stress_gear"),
                          ("load_torque_N_m",), "--fe-ltca")
        fe = _same_point(fe, design, load, "--fe-ltca")
    envelope = None
    if args.fe_envelope:
        envelope = _same_point(open_dataset(
            args.fe_envelope, "FE envelope", ("max_contact_pressure", "root_stress_pinion",
                                              "root_stress_gear", "displacement"),
            ("load_torque_N_m",), "--fe-envelope"), design, load, "--fe-envelope")
    ds = rating_dataset(result, design, material, conditions, source, fe, envelope, cases)
    write_dataset(ds, args.out)
    ratio = design.gear_teeth / design.pinion_teeth
    return (f"sigma_H {result.contact_stress / 1e6:.0f} MPa (S_H "
            f"{min(result.contact_safety):.2f}), sigma_F {result.root_stress[0] / 1e6:.0f} / "
            f"{result.root_stress[1] / 1e6:.0f} MPa (S_F {result.bending_safety[0]:.2f} / "
            f"{result.bending_safety[1]:.2f}); rated gear torque "
            f"{result.rated_pinion_torque_contact * ratio:.0f} N m (pitting), "
            f"{result.rated_pinion_torque_bending * ratio:.0f} N m (root) against {load:g} N m "
            f"-> {args.out}")


def _dynamic_factor(run, after, option):
    """A run's dynamic factor over its steady state from ``after`` [s], or a CommandError
    when the run's full-rate record holds none of it."""
    from lsbg.aggregate.summary import run_dynamic_factor

    if "time_full" not in run.coords or float(run["time_full"].max()) <= after:
        raise CommandError(f"{option} {run.encoding.get('source', '')}: its full-rate record "
                           f"ends before the steady state (statistics.steady_state_after_s = "
                           f"{after:g} s): no dynamic factor")
    return run_dynamic_factor(run, after)


def _same_point(ds, design, load, option):
    """``ds`` if it was computed for ``design`` (and, unless None, at ``load`` [N m]),
    else a CommandError."""
    source = ds.encoding.get("source", "")
    if load is not None and not math.isclose(float(ds.attrs["load_torque_N_m"]), load,
                                             rel_tol=1e-9):
        raise CommandError(f"{option} {source}: computed at "
                           f"{float(ds.attrs['load_torque_N_m']):g} N m, the rating's load is "
                           f"{load:g} N m")
    difference = design.attrs_difference(ds.attrs)
    if difference is not None:
        key, stored, value = difference
        raise CommandError(f"{option} {source}: design {key} = {stored!r}, the geometry's "
                           f"{value!r}")
    return ds
