"""The dynamic-factor curve: ``lsbg mesh-mode``, ``speed-run`` and ``speed-curve``."""

from __future__ import annotations

import math

from lsbg.cli.options import (CommandError, add_config_options, add_output, checked,
                              contact_of, driveline_of, flanks_of, simulation_of,
                              slice_stiffness_of)
from lsbg.cli.simulate import RUN_SECTIONS, add_run_options, simulate_to

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
    add_config_options(parser, ("contact", "flank_modification", "misalignment"))
    add_output(parser, metavar="TABLE.csv", required=False,
               help="also write the figures as a CSV table, one row per geometry: mesh "
                    "stiffness [N/um], gear inertia [kg m^2], f_n [Hz], the resonance pinion "
                    "speeds [deg/s]")
    parser.set_defaults(handler=run_mesh_mode)


def run_mesh_mode(args):
    """Handler of ``lsbg mesh-mode``: its figures, a few lines per geometry."""
    import pandas as pd

    from lsbg.dynamics import load_model
    from lsbg.experiments.speed import resonance_speeds

    params, flanks = contact_of(args.settings, model="line"), flanks_of(args.settings)
    rows, lines = [], []
    for geometry in args.geometry:
        model = load_model(geometry, params, flanks)
        contact, design = model.contact, model.pair.design
        natural = contact.natural_frequency(model.gear_inertia)
        speeds = resonance_speeds(natural, design.pinion_teeth)
        lines += [f"{design.trace}, spiral angle {math.degrees(design.spiral_angle):g} deg",
                  f"  mean mesh stiffness      {contact.mean_mesh_stiffness() / 1e6:10.4g} N/um "
                  f"(torsional {contact.mean_torsional_stiffness():.4g} N m/rad)",
                  f"  gear inertia             {model.gear_inertia:10.4g} kg m^2",
                  f"  natural frequency f_n    {natural:10.4g} Hz"]
        lines += [f"  f_mesh = f_n/{order} at pinion {math.degrees(speed):10.6g} deg/s "
                  f"({speed * 30 / math.pi:.6g} rpm)" for order, speed in zip((1, 2, 3), speeds)]
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
    return lines


# ------------------------------------------------------------ speed run
def add_speed_run_parser(subparsers):
    """``lsbg speed-run``: one run of the pinion-speed sweep."""
    parser = subparsers.add_parser(
        "speed-run", help="one run of the pinion-speed sweep (line model)",
        description="Run the line model of --geometry at simulation.pinion_speed_deg_s with "
                    "the settings of a speed sweep (lsbg.experiments.speed.speed_settings and "
                    "the 'speed_sweep' section: a short ramp, a settling time, a steady window "
                    "of whole mesh cycles, a full-rate record fast enough for the mesh "
                    "harmonics; the sweep sets the duration, samples and full-rate record); the "
                    "rest of the settings from the configuration. Writes the run as 'lsbg "
                    "simulate' does.")
    add_run_options(parser)
    add_config_options(parser, (*RUN_SECTIONS, "speed_sweep"))
    add_output(parser, metavar="RUN.nc")
    parser.set_defaults(handler=run_speed_run)


def run_speed_run(args):
    """Handler of ``lsbg speed-run``: its summary line."""
    from lsbg.experiments.speed import speed_keywords, speed_settings
    from lsbg.solid.directory import read_design

    base = simulation_of(args.settings, args.engine)
    params = contact_of(args.settings, model="line")
    teeth = read_design(args.geometry).pinion_teeth
    settings = checked(lambda: speed_settings(base, base.pinion_speed, teeth,
                                              **speed_keywords(args.settings["speed_sweep"])))
    slices = slice_stiffness_of(args.fe_ltca, params, args.geometry, settings.load_torque)
    speed = math.degrees(base.pinion_speed)
    written = simulate_to(args.out, args.geometry, settings, params, flanks_of(args.settings),
                          slices, f"{speed:g} deg/s", driveline_of(args.settings))
    return f"{speed:g} deg/s, {settings.duration:.3g} s simulated {written}"


# ----------------------------------------------------------- speed curve
def add_speed_curve_parser(subparsers):
    """``lsbg speed-curve``: the runs of a speed sweep -> the dynamic-factor curve."""
    parser = subparsers.add_parser(
        "speed-curve", help="the dynamic-factor curve of a pinion-speed sweep",
        description="From the runs of 'lsbg speed-run' (each trace at the same speeds): RMS "
                    "dynamic transmission error, dynamic factor and gear-speed fluctuation per "
                    "trace and pinion speed, the transmission-error spectra on one frequency "
                    "grid, the natural frequency of each trace's mesh mode and the speeds at "
                    "which the mesh frequency meets it (NetCDF, CF-1.11). The runs share one "
                    "boundary (simulation.boundary).")
    parser.add_argument("--runs", nargs="+", required=True, metavar="RUN.nc", help="run files")
    parser.add_argument("--orders", type=int, default=3, metavar="K",
                        help="mesh harmonics 1..K whose resonance speeds (k f_mesh = f_n) the "
                             "curve gives (default: 3)")
    add_output(parser, metavar="CURVE.nc")
    parser.set_defaults(handler=run_speed_curve)


def run_speed_curve(args):
    """Handler of ``lsbg speed-curve``: a line per trace."""
    import numpy as np

    from lsbg.dynamics.dataset import open_runs
    from lsbg.files import write_dataset
    from lsbg.experiments.speed import speed_curve

    if args.orders < 3:
        raise CommandError(f"--orders {args.orders}: must be at least 3 (the curve's table "
                           f"gives f_n, f_n/2 and f_n/3)")
    try:
        curve = speed_curve(open_runs(args.runs), orders=args.orders)
    except (OSError, ValueError) as err:
        raise CommandError(f"--runs: {err}") from None
    write_dataset(curve, args.out)
    speeds = curve["pinion_speed"].values
    lines = []
    for trace in curve["trace"].values:
        natural = float(curve["natural_frequency"].sel(trace=trace))
        ratio = curve["mesh_frequency"].values / natural
        peak = curve["dynamic_factor"].sel(trace=trace)
        at = float(speeds[int(np.argmax(peak.values))])
        lines.append(f"{trace}, {curve.attrs['solver_boundary']}: f_n {natural:.4g} Hz; "
                     f"{speeds.size} speeds "
                     f"{speeds.min():.5g}-{speeds.max():.5g} deg/s (f_mesh/f_n "
                     f"{ratio.min():.3g}-{ratio.max():.3g}); peak dynamic factor "
                     f"{float(peak.max()):.4g} at {at:.5g} deg/s")
    return lines + [f"-> {args.out}"]
