"""Parameter sweeps on the command line: ``lsbg sweep-run`` and ``lsbg sweep-combine``.

``sweep-run`` runs a batch of sweep points (:mod:`lsbg.experiments.sweeps`) at one design
point in one process, so that a cluster pays its per-job start-up once per
batch; ``sweep-combine`` stacks a sweep's runs into one dataset with a
coordinate per swept key (:mod:`lsbg.aggregate.sweep_dataset`).
"""

from __future__ import annotations

import sys

from lsbg.cli.options import CommandError, check_output, read_study_sections

__all__ = ["add_sweep_run_parser", "add_sweep_combine_parser"]


def add_sweep_run_parser(subparsers):
    """``lsbg sweep-run``: several sweep points of one design point, one process."""
    parser = subparsers.add_parser(
        "sweep-run", help="run a batch of parameter-sweep points at one design point",
        description="For each --point RUN.nc KEY=VALUE ..., simulate the pair of --geometry "
                    "with the settings of --config and the point's values (KEY is "
                    "section.key of the design, contact, simulation, flank_modification or "
                    "misalignment section, in the configuration's units) and write the run to "
                    "RUN.nc, its values recorded as attributes sweep_<section>_<key>. A point "
                    "that sets design keys builds its own geometry (in a temporary folder). "
                    "Every point is checked before the first run; a blow-up stops the batch "
                    "with exit code 3, the points before it written.")
    parser.add_argument("--geometry", required=True, metavar="DIR",
                        help="geometry directory of the design point (lsbg geometry)")
    parser.add_argument("--config", metavar="FILE.yaml",
                        help="study configuration (results/config.yaml): the sections the "
                             "points change")
    parser.add_argument("--engine", choices=("pybullet", "scipy", "compiled"), default="compiled",
                        help="integrator (default: compiled)")
    parser.add_argument("--contact-model", choices=("point", "line"), default="line",
                        help="contact model (default: line)")
    parser.add_argument("--sweep", required=True, metavar="NAME",
                        help="the sweep's name, recorded in every run")
    parser.add_argument("--kind", choices=("values", "product", "combinations"),
                        default="values", help="how the sweep's points were made (recorded)")
    parser.add_argument("--point", action="append", nargs="+", required=True,
                        metavar="RUN.nc KEY=VALUE",
                        help="an output file and the point's values; repeatable")
    parser.set_defaults(handler=run_sweep_run)


def _point(words):
    """(output path, {section.key: value}) of a --point's words."""
    import yaml

    from lsbg.experiments.sweeps import SWEEPABLE_SECTIONS

    out, *assignments = words
    if "=" in out:
        raise CommandError(f"--point {' '.join(words)}: the output file comes first")
    values = {}
    for text in assignments:
        key, sep, value = text.partition("=")
        section = key.split(".", 1)[0]
        if not sep or "." not in key or section not in SWEEPABLE_SECTIONS:
            raise CommandError(f"--point {out} {text!r}: must be SECTION.KEY=VALUE with SECTION "
                               f"one of {', '.join(SWEEPABLE_SECTIONS)}")
        values[key] = yaml.safe_load(value)
    if not values:
        raise CommandError(f"--point {out}: no KEY=VALUE")
    return out, values


def _point_objects(args, sections, values, design_dir):
    """(settings, contact parameters, flanks, design or None) of one point."""
    from lsbg.contact import ContactParameters
    from lsbg.gear.design import GearPairDesign
    from lsbg.dynamics import SimulationSettings
    from lsbg.solid.directory import read_design
    from lsbg.tca.separation import RealFlanks

    settings = SimulationSettings.from_config(sections["simulation"], engine=args.engine)
    # (a sweep's runs take the uniform bed: the FE slice stiffness is the study's own
    # design points', at their load; lsbg.experiments.sweeps.FIXED_KEYS)
    params = ContactParameters.from_config({**sections["contact"], "model": args.contact_model,
                                            "compliance": "uniform"})
    flanks = RealFlanks.from_config(sections["flank_modification"], sections["misalignment"])
    design = None
    if any(k.startswith("design.") for k in values):
        base = read_design(design_dir)
        design = GearPairDesign.from_config({**base.to_config(), **sections["design"]})
    return settings, params, flanks, design


def run_sweep_run(args):
    """Handler of ``lsbg sweep-run`` [exit code]."""
    import tempfile

    from lsbg.dynamics import SimulationError, simulate
    from lsbg.solid.directory import read_design
    from lsbg.files import write_dataset
    from lsbg.experiments.sweeps import point_sections, swept_attribute

    study = dict(zip(("design", "contact", "simulation", "flank_modification", "misalignment"),
                     read_study_sections(args.config, "design", "contact", "simulation",
                                         "flank_modification", "misalignment")))
    read_design(args.geometry)  # the design point exists and is whole
    points = []
    for words in args.point:
        out, values = _point(words)
        check_output(out, "--point")
        sections = point_sections(study, values)
        try:
            points.append((out, values, *_point_objects(args, sections, values, args.geometry)))
        except ValueError as err:
            raise CommandError(f"--point {out}: {err}") from None
    command = " ".join(["lsbg", *sys.argv[1:]])
    for out, values, settings, params, flanks, design in points:
        with tempfile.TemporaryDirectory(prefix="lsbg-sweep-") as scratch:
            geometry = args.geometry
            if design is not None:
                from lsbg.solid.export import write_geometry

                # the design point of this trace and angle with the point's design keys
                base = read_design(args.geometry)
                geometry = f"{scratch}/geometry"
                write_geometry(design.replace(trace=base.trace, spiral_angle=base.spiral_angle),
                               geometry)
            try:
                ds = simulate(geometry, settings, params, command=command, flanks=flanks)
            except SimulationError as err:
                print(f"lsbg sweep-run: {out}: simulation stopped: {err}", file=sys.stderr)
                return 3
        ds.attrs.update({"sweep_name": args.sweep, "sweep_kind": args.kind,
                         "sweep_keys": " ".join(values)})
        ds.attrs.update({swept_attribute(k): v for k, v in values.items()})
        write_dataset(ds, out)
        print(f"lsbg sweep-run: {', '.join(f'{k} = {v!r}' for k, v in values.items())} -> {out} "
              f"({ds.attrs['wall_time_s']:.1f} s wall)")
    return 0


def add_sweep_combine_parser(subparsers):
    """``lsbg sweep-combine``: a sweep's runs -> one dataset and a summary table."""
    parser = subparsers.add_parser(
        "sweep-combine", help="combine a parameter sweep's runs into one dataset",
        description="Stack the runs of one sweep (lsbg sweep-run) into one NetCDF dataset "
                    "with a coordinate per swept key (its grid for a product sweep) beside "
                    "the trace and the spiral angle: per run, the mean, the output samples' std "
                    "and the full-rate std of each quantity and the dynamic factor. --csv "
                    "writes the summary rows (lsbg summary) with a column per swept key.")
    parser.add_argument("--runs", nargs="+", required=True, metavar="RUN.nc",
                        help="the sweep's runs")
    parser.add_argument("--config", metavar="FILE.yaml",
                        help="study configuration: its statistics section")
    parser.add_argument("--out", required=True, metavar="SWEEP.nc", help="output NetCDF file")
    parser.add_argument("--csv", metavar="SWEEP.csv", help="also write the summary rows")
    parser.set_defaults(handler=run_sweep_combine)


def run_sweep_combine(args):
    """Handler of ``lsbg sweep-combine`` [exit code]."""
    from lsbg.dynamics.dataset import open_run
    from lsbg.files import write_dataset
    from lsbg.aggregate.summary import statistics_options
    from lsbg.aggregate.sweep_dataset import sweep_dataset, sweep_rows

    check_output(args.out, "--out")
    if args.csv:
        check_output(args.csv, "--csv")
    (statistics,) = read_study_sections(args.config, "statistics")
    try:
        options = statistics_options(statistics)
    except ValueError as err:
        raise CommandError(str(err)) from None
    runs = [open_run(path) for path in args.runs]
    try:
        table = sweep_rows(runs, **options)  # once: the dataset is built from these rows
        ds = sweep_dataset(runs, rows=table, **options)
    except ValueError as err:
        raise CommandError(str(err)) from None
    write_dataset(ds, args.out)
    if args.csv:
        from lsbg.files import write_atomically

        write_atomically(args.csv, lambda tmp: table.to_csv(tmp, index=False))
    print(f"lsbg sweep-combine: {len(runs)} runs of {ds.attrs['sweep_name']} over "
          f"{', '.join(ds.attrs['sweep_keys'].split())} -> {args.out}")
    return 0
