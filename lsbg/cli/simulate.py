"""Meshing simulations: ``lsbg simulate``, ``sensitivity`` and ``convergence``."""

from __future__ import annotations

from lsbg.cli.options import (CommandError, add_case_options, add_config_options,
                              add_engine_option, add_fe_ltca_option, add_geometry_input,
                              add_output, check_output, command_line, contact_of, driveline_of,
                              flanks_of, parse_pairs, simulation_of, slice_stiffness_of)

__all__ = ["add_simulate_parser", "add_sensitivity_parser", "add_convergence_parser",
           "simulate_to"]

#: The sections a run reads.
RUN_SECTIONS = ("simulation", "driveline", "contact", "flank_modification", "misalignment")


def add_run_options(parser, engine="pybullet"):
    """Add what every meshing run reads: ``--geometry``, ``--engine``, the configuration
    and ``--fe-ltca``."""
    add_geometry_input(parser)
    add_engine_option(parser, default=engine)
    add_fe_ltca_option(parser)


def simulate_to(path, geometry, settings, params, flanks, slices, label=None, driveline=None):
    """Simulate one run (:func:`lsbg.dynamics.simulate`) and write it to ``path``.

    Parameters
    ----------
    path : str
        The run file to write (NetCDF).
    geometry : str
        The design point's geometry directory.
    settings : lsbg.dynamics.SimulationSettings
    params : lsbg.contact.ContactParameters
    flanks : lsbg.tca.separation.RealFlanks
    slices : lsbg.contact.slices.SliceStiffness or None
        The tooth's slice stiffness (:func:`slice_stiffness_of`).
    label : str, optional
        Put before the message of a blow-up (the case, the speed).
    driveline : dict, optional
        The ``driveline`` section (:func:`driveline_of`), read under the
        driveline boundary.

    Returns
    -------
    str
        ``-> PATH (S s wall)``: where it went and its wall-clock time [s].

    Raises
    ------
    lsbg.dynamics.SimulationError
        On a blow-up; nothing is written.
    """
    from lsbg.dynamics import SimulationError, simulate
    from lsbg.files import write_dataset

    try:
        ds = simulate(geometry, settings, params, command=command_line(), flanks=flanks,
                      slice_stiffness=slices, driveline=driveline)
    except SimulationError as err:
        if label is None:
            raise
        raise SimulationError(f"{label}: {err}") from None
    write_dataset(ds, path)
    return f"-> {path} ({ds.attrs['wall_time_s']:.1f} s wall)"


def add_simulate_parser(subparsers):
    """``lsbg simulate``: one meshing simulation -> one NetCDF time series."""
    parser = subparsers.add_parser(
        "simulate", help="simulate the meshing of one design point",
        description="Simulate the meshing of the pair in --geometry (paper §3: pinion speed "
                    "ramped to 7703 deg/s, gear loaded with 1964.99 N m; the 'simulation' and "
                    "'contact' sections; under simulation.boundary=driveline the torsional "
                    "driveline of the 'driveline' section around the mesh) and write the time "
                    "series to --out (NetCDF, CF-1.11). A blow-up (NaN, penetration beyond d, "
                    "runaway speed) stops the run with exit code 3 and writes nothing.")
    add_run_options(parser)
    add_config_options(parser, RUN_SECTIONS)
    add_output(parser, metavar="RUN.nc")
    parser.set_defaults(handler=run_simulate)


def run_simulate(args):
    """Handler of ``lsbg simulate``: its summary line."""
    settings = simulation_of(args.settings, args.engine)
    params = contact_of(args.settings)
    flanks = flanks_of(args.settings)
    slices = slice_stiffness_of(args.fe_ltca, params, args.geometry, settings.load_torque)
    written = simulate_to(args.out, args.geometry, settings, params, flanks, slices,
                          driveline=driveline_of(args.settings))
    boundary = "" if settings.boundary == "prescribed_pinion" else ", driveline"
    return f"{settings.engine} engine, {params.model} model{boundary} {written}"


# ------------------------------------------------------------ sensitivity
def add_sensitivity_parser(subparsers):
    """``lsbg sensitivity``: line-model runs with one contact setting scaled per case."""
    parser = subparsers.add_parser(
        "sensitivity", help="line-model runs with one setting scaled or switched per case",
        description="For each --case KEY=FACTOR, run the line model of --geometry with the "
                    "setting KEY scaled by FACTOR (or switched, or displaced), and write it to "
                    "--out with {case} replaced by the case's name (KEY_xFACTOR, KEY_VALUE, "
                    "displaced_CORNER). One process for all cases; every case is checked "
                    "before the first run. KEY: mesh_damping_ratio, "
                    "line_stiffness_N_per_mm_um, slices (FACTOR scales it), crowning (FACTOR "
                    "scales the flank_modification's crowning and bias; 0: conjugate flanks), "
                    "compliance=fe / compliance=uniform (the line model on the tooth's FE "
                    "stiffness, from --fe-ltca, or on the uniform bed), displacement=envelope "
                    "(one case per corner of the displacement envelope: misalignment_map.axes "
                    "at +-its range), pinion_speed (FACTOR scales the pinion's speed).")
    add_run_options(parser)
    add_config_options(parser, (*RUN_SECTIONS, "misalignment_map"))
    add_case_options(parser, "dynamics", out=False)
    parser.add_argument("--out", required=True, metavar="RUN.nc",
                        help="output NetCDF file template with the field {case}")
    parser.set_defaults(handler=run_sensitivity)


def run_sensitivity(args):
    """Handler of ``lsbg sensitivity``: a line per case."""
    from lsbg.cli.cases import sensitivity_cases
    from lsbg.experiments.sensitivity import case_simulation, parse_case

    if not args.case:
        raise CommandError("--case: at least one case (e.g. --case crowning=0.5)")
    settings = simulation_of(args.settings, args.engine)
    flanks_of(args.settings)  # checks the flank sections before any work
    cases = []
    for name, params, flanks, path in sensitivity_cases(args, "dynamics", args.out, "--out",
                                                        model="line"):
        # an operating case (the pinion's speed) runs with its own simulation section
        simulation = case_simulation(*parse_case(name), args.settings["simulation"])
        own = simulation_of({**args.settings, "simulation": simulation}, args.engine)
        cases.append((name, own, params, flanks,
                      slice_stiffness_of(args.fe_ltca, params, args.geometry, own.load_torque),
                      path))
    lines = []
    driveline = driveline_of(args.settings)
    for name, own, params, flanks, slices, path in cases:
        written = simulate_to(path, args.geometry, own, params, flanks, slices, f"case {name}",
                              driveline)
        lines.append(f"{name} {written}")
    return lines


# ------------------------------------------------------------ convergence
def add_convergence_parser(subparsers):
    """``lsbg convergence``: standard deviations against time step and tolerance."""
    parser = subparsers.add_parser(
        "convergence", help="convergence table of one design point",
        description="Run one design point with pybullet at dt = 4e-6, 2e-6, 1e-6 s and the "
                    "scipy and compiled engines at rtol = 1e-6, 1e-8, 1e-10 (or the engines of "
                    "--engines), and write the standard deviations of gear speed and tangential "
                    "force after statistics.steady_state_after_s to --out (CSV). A run given "
                    "with --known (lsbg simulate) is read instead of run again.")
    add_run_options(parser)
    add_config_options(parser, (*RUN_SECTIONS, "statistics"))
    parser.add_argument("--engines", nargs="+", choices=("pybullet", "scipy", "compiled"),
                        metavar="ENGINE", help="engines in the table (default: all three)")
    parser.add_argument("--known", nargs="+", default=[], metavar="RUN.nc",
                        help="runs already made; those of the table's settings are reused")
    parser.add_argument("--default-run", action="append", default=[], metavar="ENGINE=RUN.nc",
                        help="write the table's run of ENGINE at the default settings to RUN.nc "
                             "(as 'lsbg simulate' would; repeatable)")
    add_output(parser, metavar="TABLE.csv", help="output CSV file")
    parser.set_defaults(handler=run_convergence)


def run_convergence(args):
    """Handler of ``lsbg convergence``: the table."""
    from lsbg.dynamics import load_model
    from lsbg.dynamics.dataset import open_runs, run_dataset
    from lsbg.experiments.verification import convergence_study
    from lsbg.files import write_atomically, write_dataset

    settings = simulation_of(args.settings, args.engine)
    params = contact_of(args.settings)
    engines = args.engines or ("pybullet", "scipy", "compiled")
    outputs = parse_pairs(args.default_run, "--default-run", keys=engines)
    for path in outputs.values():
        check_output(path, "--default-run")
    slices = slice_stiffness_of(args.fe_ltca, params, args.geometry, settings.load_torque)
    model = load_model(args.geometry, params, flanks_of(args.settings), slices,
                       driveline_of(args.settings) if settings.boundary == "driveline" else None)
    try:
        known = open_runs(args.known)
    except (OSError, ValueError) as err:
        raise CommandError(f"--known: {err}") from None
    made = {}
    try:
        table = convergence_study(
            model, settings, steady_start=args.settings["statistics"]["steady_state_after_s"],
            engines=engines, known=known, default_runs=made)
    except ValueError as err:
        raise CommandError(f"--known: {err}") from None
    missing = sorted(set(outputs) - set(made))
    if missing:
        raise CommandError(f"--default-run: the {', '.join(missing)} run at the default "
                           f"settings was given with --known, not made here")
    for engine, path in outputs.items():
        write_dataset(run_dataset(made[engine], model, settings.replace(engine=engine),
                                  command_line()), path)
    write_atomically(args.out, lambda tmp: table.to_csv(tmp, index=False))
    return table.to_string(index=False).splitlines()
