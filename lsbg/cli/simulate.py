"""Meshing simulations: ``lsbg simulate``, ``sensitivity`` and ``convergence``."""

from __future__ import annotations

import sys

from lsbg.cli.options import (CommandError, add_fe_ltca_option, add_simulation_options,
                              check_output, flanks_from_args, simulation_from_args,
                              slice_stiffness_from_args)

__all__ = ["add_simulate_parser", "add_sensitivity_parser", "add_convergence_parser"]


def add_simulate_parser(subparsers):
    """``lsbg simulate``: one meshing simulation -> one NetCDF time series."""
    parser = subparsers.add_parser(
        "simulate", help="simulate the meshing of one design point",
        description="Simulate the meshing of the pair in --geometry (paper §3: pinion speed "
                    "ramped to 7703 deg/s, gear loaded with 1964.99 N m) and write the time "
                    "series to --out (NetCDF, CF-1.11). A blow-up (NaN, penetration beyond d, "
                    "runaway speed) stops the run with exit code 3 and writes nothing.")
    add_simulation_options(parser)
    add_fe_ltca_option(parser)
    parser.add_argument("--out", required=True, metavar="RUN.nc", help="output NetCDF file")
    parser.set_defaults(handler=run_simulate)


def run_simulate(args):
    """Handler of ``lsbg simulate`` [exit code]."""
    from lsbg.dynamics import SimulationError, simulate
    from lsbg.files import write_dataset

    settings, params = simulation_from_args(args)
    flanks = flanks_from_args(args)
    slices = slice_stiffness_from_args(args, params, args.geometry, settings.load_torque)
    check_output(args.out, "--out")
    try:
        ds = simulate(args.geometry, settings, params, command=" ".join(["lsbg", *sys.argv[1:]]),
                      flanks=flanks, slice_stiffness=slices)
    except SimulationError as err:
        print(f"lsbg simulate: simulation stopped: {err}", file=sys.stderr)
        return 3
    write_dataset(ds, args.out)
    print(f"lsbg simulate: {settings.engine} engine, {params.model} model -> {args.out} "
          f"({ds.attrs['wall_time_s']:.1f} s wall)")
    return 0


# ------------------------------------------------------------ sensitivity
def add_sensitivity_parser(subparsers):
    """``lsbg sensitivity``: line-model runs with one contact setting scaled per case."""
    parser = subparsers.add_parser(
        "sensitivity", help="line-model runs with one contact setting scaled per case",
        description="For each --case KEY=FACTOR, run the line model of --geometry with the "
                    "setting KEY of --config scaled by FACTOR (or switched, or displaced), "
                    "and write it to --out with {case} replaced by the case's name "
                    "(KEY_xFACTOR, KEY_VALUE, displaced_CORNER). One process for all cases; "
                    "every case is checked before the first run.")
    add_simulation_options(parser, contact_model=False)
    add_fe_ltca_option(parser)
    parser.add_argument("--case", action="append", required=True, metavar="KEY=FACTOR",
                        help="a case: KEY one of mesh_damping_ratio, line_stiffness_N_per_mm_um, "
                             "slices (FACTOR scales it), crowning (FACTOR scales the "
                             "flank_modification's crowning and bias; 0: conjugate flanks), "
                             "compliance=fe / compliance=uniform (the line model on the tooth's "
                             "FE stiffness, from --fe-ltca, or on the uniform bed), or "
                             "displacement=envelope (one case per corner of the displacement "
                             "envelope: misalignment_map.axes of --config at +-its range); "
                             "repeatable")
    parser.add_argument("--out", required=True, metavar="RUN.nc",
                        help="output NetCDF file template with the field {case}")
    parser.set_defaults(handler=run_sensitivity, contact_model="line")


def run_sensitivity(args):
    """Handler of ``lsbg sensitivity`` [exit code]."""
    from lsbg.cli.cases import cases_from_args
    from lsbg.dynamics import SimulationError, simulate
    from lsbg.files import write_dataset

    settings, _ = simulation_from_args(args)
    flanks_from_args(args)  # checks the flank sections before any work
    cases = []
    for name, params, flanks, path in cases_from_args(args, "dynamics", args.out, "--out"):
        slices = slice_stiffness_from_args(args, params, args.geometry, settings.load_torque)
        cases.append((name, params, flanks, slices, path))
    command = " ".join(["lsbg", *sys.argv[1:]])
    for name, params, flanks, slices, path in cases:
        try:
            ds = simulate(args.geometry, settings, params, command=command, flanks=flanks,
                          slice_stiffness=slices)
        except SimulationError as err:
            print(f"lsbg sensitivity: case {name}: simulation stopped: {err}", file=sys.stderr)
            return 3
        write_dataset(ds, path)
        print(f"lsbg sensitivity: {name} -> {path} ({ds.attrs['wall_time_s']:.1f} s wall)")
    return 0


# ------------------------------------------------------------ convergence
def add_convergence_parser(subparsers):
    """``lsbg convergence``: standard deviations against time step and tolerance."""
    parser = subparsers.add_parser(
        "convergence", help="convergence table of one design point",
        description="Run one design point with pybullet at dt = 4e-6, 2e-6, 1e-6 s and the "
                    "scipy and compiled engines at rtol = 1e-6, 1e-8, 1e-10 (or the engines of "
                    "--engines), and write the standard deviations of gear speed and tangential "
                    "force after the steady-state start to --out (CSV). A run given with "
                    "--known (lsbg simulate) is read instead of run again.")
    add_simulation_options(parser)
    parser.add_argument("--engines", nargs="+", choices=("pybullet", "scipy", "compiled"),
                        metavar="ENGINE", help="engines in the table (default: all three)")
    parser.add_argument("--known", nargs="+", default=[], metavar="RUN.nc",
                        help="runs already made; those of the table's settings are reused")
    parser.add_argument("--default-run", action="append", default=[], metavar="ENGINE=RUN.nc",
                        help="write the table's run of ENGINE at the default settings to RUN.nc "
                             "(as 'lsbg simulate' would; repeatable)")
    parser.add_argument("--steady-state-after", type=float, default=0.2, metavar="S",
                        help="start of the steady state [s] (default 0.2)")
    add_fe_ltca_option(parser)
    parser.add_argument("--out", required=True, metavar="TABLE.csv", help="output CSV file")
    parser.set_defaults(handler=run_convergence)


def run_convergence(args):
    """Handler of ``lsbg convergence`` [exit code]."""
    from lsbg.dynamics import SimulationError, load_model
    from lsbg.dynamics.dataset import open_runs, run_dataset
    from lsbg.files import write_atomically, write_dataset
    from lsbg.experiments.verification import convergence_study

    settings, params = simulation_from_args(args)
    engines = args.engines or ("pybullet", "scipy", "compiled")
    outputs = {}
    for text in args.default_run:
        engine, sep, path = text.partition("=")
        if not sep or engine not in engines or not path:
            raise CommandError(f"--default-run {text!r}: must be ENGINE=RUN.nc with ENGINE one "
                               f"of the table's engines {list(engines)}")
        outputs[engine] = path
    for path in outputs.values():
        check_output(path, "--default-run")
    check_output(args.out, "--out")
    slices = slice_stiffness_from_args(args, params, args.geometry, settings.load_torque)
    model = load_model(args.geometry, params, flanks_from_args(args), slices)
    try:
        known = open_runs(args.known)
    except (OSError, ValueError) as err:
        raise CommandError(f"--known: {err}") from None
    made = {}
    try:
        table = convergence_study(model, settings, steady_start=args.steady_state_after,
                                  engines=engines, known=known, default_runs=made)
    except ValueError as err:
        raise CommandError(f"--known: {err}") from None
    except SimulationError as err:
        print(f"lsbg convergence: simulation stopped: {err}", file=sys.stderr)
        return 3
    missing = sorted(set(outputs) - set(made))
    if missing:
        raise CommandError(f"--default-run: the {', '.join(missing)} run at the default "
                           f"settings was given with --known, not made here")
    command = " ".join(["lsbg", *sys.argv[1:]])
    for engine, path in outputs.items():
        write_dataset(run_dataset(made[engine], model, settings.replace(engine=engine), command),
                      path)
    write_atomically(args.out, lambda tmp: table.to_csv(tmp, index=False))
    print(table.to_string(index=False))
    return 0


