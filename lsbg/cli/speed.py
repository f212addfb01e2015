"""The dynamic-factor curve: ``lsbg mesh-mode``, ``speed-run`` and ``speed-curve``."""

from __future__ import annotations

import math
import sys

from lsbg.cli.options import (
    CommandError,
    add_contact_options,
    add_fe_ltca_option,
    add_simulation_options,
    check_output,
    contact_from_args,
    flanks_from_args,
    simulation_from_args,
    slice_stiffness_from_args,
)

__all__ = ["add_mesh_mode_parser", "add_speed_run_parser", "add_speed_curve_parser"]


# ------------------------------------------------------------ mesh mode
def add_mesh_mode_parser(subparsers):
    """``lsbg mesh-mode``: the line model's mesh stiffness and natural frequency."""
    parser = subparsers.add_parser(
        "mesh-mode", help="mesh stiffness, natural frequency and resonance speeds",
        description="Print the line model's mean mesh stiffness of the pair in --geometry, "
                    "the gear's inertia, the natural frequency f_n of the mesh mode (the gear "
                    "on the mesh spring, the pinion on its prescribed speed) and the pinion "
                    "speeds at which the mesh frequency meets f_n, f_n/2 and f_n/3: where a "
                    "pinion-speed sweep must reach. Several --geometry directories: one after "
                    "the other; --out writes them as a table (one row each).")
    parser.add_argument("--geometry", required=True, nargs="+", metavar="DIR",
                        help="geometry directory written by 'lsbg geometry' (or several)")
    add_contact_options(parser, model=False)
    parser.add_argument("--out", metavar="TABLE.csv",
                        help="also write the figures as a CSV table, one row per geometry: "
                             "mesh stiffness [N/um], gear inertia [kg m^2], f_n [Hz], the "
                             "resonance pinion speeds [deg/s]")
    parser.set_defaults(handler=run_mesh_mode, contact_model="line")


def run_mesh_mode(args):
    """Handler of ``lsbg mesh-mode`` [exit code]."""
    import pandas as pd

    from lsbg.dynamics import load_model
    from lsbg.experiments.speed import resonance_speeds

    if args.out:
        check_output(args.out, "--out")
    params, flanks = contact_from_args(args), flanks_from_args(args)
    rows = []
    for geometry in args.geometry:
        model = load_model(geometry, params, flanks)
        contact, design = model.contact, model.pair.design
        natural = contact.natural_frequency(model.gear_inertia)
        speeds = resonance_speeds(natural, design.pinion_teeth)
        print(f"lsbg mesh-mode: {design.trace}, spiral angle "
              f"{math.degrees(design.spiral_angle):g} deg")
        print(f"  mean mesh stiffness      {contact.mean_mesh_stiffness() / 1e6:10.4g} N/um "
              f"(torsional {contact.mean_torsional_stiffness():.4g} N m/rad)")
        print(f"  gear inertia             {model.gear_inertia:10.4g} kg m^2")
        print(f"  natural frequency f_n    {natural:10.4g} Hz")
        for order, speed in zip((1, 2, 3), speeds):
            print(f"  f_mesh = f_n/{order} at pinion {math.degrees(speed):10.6g} deg/s "
                  f"({speed * 30 / math.pi:.6g} rpm)")
        rows.append({"trace": design.trace,
                     "spiral_angle_deg": round(math.degrees(design.spiral_angle), 9),
                     "mesh_stiffness_N_per_um": contact.mean_mesh_stiffness() / 1e6,
                     "gear_inertia_kg_m2": model.gear_inertia,
                     "natural_frequency_hz": natural,
                     **{f"resonance_speed_order_{order}_deg_s": math.degrees(speed)
                        for order, speed in zip((1, 2, 3), speeds)}})
    if args.out:
        from lsbg.files import write_atomically

        write_atomically(args.out, lambda tmp: pd.DataFrame(rows).to_csv(tmp, index=False))
    return 0


# ------------------------------------------------------------ speed run
#: Options of ``lsbg speed-run`` -> (keyword of lsbg.experiments.speed.speed_settings, type, help).
SPEED_OPTIONS = {
    "mesh_cycles": ("mesh_cycles", int, "least mesh cycles in the steady window (default 100)"),
    "min_window": ("min_window", float, "least length of the steady window [s] (default 0.05)"),
    "settle_time": ("settle_time", float,
                    "time after the ramp before the window [s] (default 0.05)"),
    "samples_per_mesh": ("samples_per_mesh", int,
                         "least full-rate samples per mesh cycle (default 32)"),
}


def add_speed_run_parser(subparsers):
    """``lsbg speed-run``: one run of the pinion-speed sweep."""
    parser = subparsers.add_parser(
        "speed-run", help="one run of the pinion-speed sweep (line model)",
        description="Run the line model of --geometry at --pinion-speed with the settings of "
                    "a speed sweep (lsbg.experiments.speed.speed_settings: a short ramp, a settling time, "
                    "a steady window of whole mesh cycles, a full-rate record fast enough for "
                    "the mesh harmonics); the rest of the settings from --config. --ramp-time "
                    "(default 0.05 s here) is the sweep's ramp; --duration, --samples, "
                    "--full-rate and --full-rate-after are the sweep's own. Writes the run as "
                    "'lsbg simulate' does.")
    add_simulation_options(parser, contact_model=False)
    add_fe_ltca_option(parser)
    for option, (_, kind, text) in SPEED_OPTIONS.items():
        parser.add_argument(f"--{option.replace('_', '-')}", dest=option, type=kind, help=text)
    parser.add_argument("--out", required=True, metavar="RUN.nc", help="output NetCDF file")
    parser.set_defaults(handler=run_speed_run, contact_model="line")


def run_speed_run(args):
    """Handler of ``lsbg speed-run`` [exit code]."""
    from lsbg.dynamics import SimulationError, simulate
    from lsbg.solid.directory import read_design
    from lsbg.files import write_dataset
    from lsbg.experiments.speed import speed_settings

    if args.pinion_speed is None:
        raise CommandError("--pinion-speed: required (the speed of this run) [deg/s]")
    fixed = [f"--{option.replace('_', '-')}" for option in
             ("duration", "samples", "full_rate", "full_rate_after")
             if getattr(args, option) is not None]
    if fixed:
        raise CommandError(f"{', '.join(fixed)}: set by the speed sweep (use --mesh-cycles, "
                           f"--min-window, --settle-time, --samples-per-mesh)")
    check_output(args.out, "--out")
    ramp = args.ramp_time
    args.ramp_time = None            # the config's ramp is the paper's run's, not the sweep's
    base, params = simulation_from_args(args)
    options = {key: getattr(args, option) for option, (key, _, _) in SPEED_OPTIONS.items()
               if getattr(args, option) is not None}
    if ramp is not None:
        options["ramp_time"] = ramp
    try:
        teeth = read_design(args.geometry).pinion_teeth
        settings = speed_settings(base, base.pinion_speed, teeth, **options)
    except (OSError, ValueError) as err:
        raise CommandError(str(err)) from None
    slices = slice_stiffness_from_args(args, params, args.geometry, settings.load_torque)
    try:
        ds = simulate(args.geometry, settings, params, command=" ".join(["lsbg", *sys.argv[1:]]),
                      flanks=flanks_from_args(args), slice_stiffness=slices)
    except SimulationError as err:
        print(f"lsbg speed-run: {args.pinion_speed:g} deg/s: simulation stopped: {err}",
              file=sys.stderr)
        return 3
    write_dataset(ds, args.out)
    print(f"lsbg speed-run: {args.pinion_speed:g} deg/s, {settings.duration:.3g} s simulated "
          f"-> {args.out} ({ds.attrs['wall_time_s']:.1f} s wall)")
    return 0


# ----------------------------------------------------------- speed curve
def add_speed_curve_parser(subparsers):
    """``lsbg speed-curve``: the runs of a speed sweep -> the dynamic-factor curve."""
    parser = subparsers.add_parser(
        "speed-curve", help="the dynamic-factor curve of a pinion-speed sweep",
        description="From the runs of 'lsbg speed-run' (each trace at the same speeds): RMS "
                    "dynamic transmission error, dynamic factor and gear-speed fluctuation per "
                    "trace and pinion speed, the transmission-error spectra on one frequency "
                    "grid, the natural frequency of each trace's mesh mode and the speeds at "
                    "which the mesh frequency meets it (NetCDF, CF-1.11).")
    parser.add_argument("--runs", nargs="+", required=True, metavar="RUN.nc", help="run files")
    parser.add_argument("--out", required=True, metavar="CURVE.nc", help="output NetCDF file")
    parser.set_defaults(handler=run_speed_curve)


def run_speed_curve(args):
    """Handler of ``lsbg speed-curve`` [exit code]."""
    import numpy as np

    from lsbg.dynamics.dataset import open_runs
    from lsbg.files import write_dataset
    from lsbg.experiments.speed import speed_curve

    check_output(args.out, "--out")
    try:
        curve = speed_curve(open_runs(args.runs))
    except (OSError, ValueError) as err:
        raise CommandError(f"--runs: {err}") from None
    write_dataset(curve, args.out)
    speeds = curve["pinion_speed"].values
    for trace in curve["trace"].values:
        natural = float(curve["natural_frequency"].sel(trace=trace))
        ratio = curve["mesh_frequency"].values / natural
        peak = curve["dynamic_factor"].sel(trace=trace)
        at = float(speeds[int(np.argmax(peak.values))])
        print(f"lsbg speed-curve: {trace}: f_n {natural:.4g} Hz; {speeds.size} speeds "
              f"{speeds.min():.5g}-{speeds.max():.5g} deg/s (f_mesh/f_n {ratio.min():.3g}-"
              f"{ratio.max():.3g}); peak dynamic factor {float(peak.max()):.4g} at {at:.5g} deg/s")
    print(f"lsbg speed-curve: -> {args.out}")
    return 0
