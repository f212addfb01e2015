"""Trace against trace: ``lsbg converge-front`` and ``lsbg trace-fronts``."""

from __future__ import annotations

from lsbg.cli.options import (CommandError, add_config_options, add_geometry_input, add_output,
                              checked, command_line)

__all__ = ["add_converge_front_parser", "add_trace_fronts_parser"]

#: The sections ``lsbg converge-front`` reads: those of ``lsbg optimise`` (the search's model).
SECTIONS = ("optimise", "flank_modification", "misalignment", "misalignment_map", "tca",
            "contact", "simulation", "rating", "tooth", "limits")


def add_converge_front_parser(subparsers):
    """``lsbg converge-front``: a trace's fronts at the release's converged positions."""
    parser = subparsers.add_parser(
        "converge-front", help="a trace's fronts at the release's converged positions",
        description="Evaluate every feasible member of the fronts (lsbg optimise, --front, one "
                    "per seed) again on the search's model (the uniform-bed loaded TCA) at the "
                    "release's converged positions (--release: its uniform_positions), drop "
                    "those whose edge_load constraint fails there and mark each seed's "
                    "non-dominated set; write them to --out (NetCDF, CF-1.11), the input of "
                    "lsbg trace-fronts (docs/optimise.md, \"Trace against trace\").")
    add_geometry_input(parser)
    add_config_options(parser, SECTIONS)
    parser.add_argument("--front", nargs="+", required=True, metavar="FRONT.nc",
                        help="the fronts of the trace's searches (lsbg optimise), one per seed")
    parser.add_argument("--release", required=True, metavar="RELEASE.nc",
                        help="the trace's release (lsbg release): its converged positions")
    add_output(parser, metavar="CONVERGED.nc")
    parser.set_defaults(handler=run_converge_front)


def run_converge_front(args):
    """Handler of ``lsbg converge-front``: its summary line."""
    import logging

    import xarray as xr

    from lsbg.files import write_dataset
    from lsbg.gear.geometry import GearPair
    from lsbg.optimise.checks import run_settings
    from lsbg.optimise.fronts import converged_front, converged_front_dataset
    from lsbg.optimise.verdict import evaluator_factory
    from lsbg.solid.directory import read_design

    design = read_design(args.geometry)
    settings = checked(lambda: run_settings(args.settings, design))
    fronts = [xr.load_dataset(path) for path in args.front]
    release = xr.load_dataset(args.release)
    traces = {str(d.attrs.get("design_trace")) for d in fronts} | {
        str(release.attrs.get("design_trace"))}
    if traces != {design.trace}:
        raise CommandError(f"--front, --release: files of {', '.join(sorted(traces))}, not of "
                           f"the geometry's {design.trace}")
    objectives = str(fronts[0].attrs["objectives"]).split()
    positions = int(release.attrs["uniform_positions"])
    log = logging.getLogger("lsbg.converge_front")
    result = converged_front(evaluator_factory(GearPair(design), settings["evaluation"]),
                             fronts, positions, objectives, log.info)
    ds = converged_front_dataset(result, objectives, {
        "history": command_line(), **{f"design_{k}": v for k, v in design.to_config().items()}})
    write_dataset(ds, args.out)
    return [f"{design.trace}: {ds.sizes['member']} members of {len(fronts)} fronts at "
            f"{positions} positions, {int(ds['kept'].sum())} on the seeds' converged fronts",
            f"-> {args.out}"]


def add_trace_fronts_parser(subparsers):
    """``lsbg trace-fronts``: the two traces' converged fronts compared."""
    parser = subparsers.add_parser(
        "trace-fronts", help="the LSBG's fronts against the SBG's, on converged objectives",
        description="Compare two traces' converged fronts (lsbg converge-front, the LSBG's "
                    "and an SBG's): the hypervolume per seed in the common box, its median and "
                    "spread, Mann-Whitney U and Vargha-Delaney A12, the additive "
                    "epsilon-indicator both ways, the share of each pooled front the other "
                    "dominates, the EAF difference in every 2-D projection with a permutation "
                    "test over the seeds' trace labels, and the verdict of docs/optimise.md's "
                    "rule; write them to --out (NetCDF, CF-1.11).")
    parser.add_argument("--converged", nargs=2, required=True, metavar="CONVERGED.nc",
                        help="the traces' converged fronts; the logarithmic trace's is the "
                             "first trace of the statistics")
    add_output(parser, metavar="TRACE_FRONTS.nc")
    parser.set_defaults(handler=run_trace_fronts)


def run_trace_fronts(args):
    """Handler of ``lsbg trace-fronts``: its summary lines."""
    import xarray as xr

    from lsbg.files import write_dataset
    from lsbg.optimise.fronts import seed_sets, trace_fronts_dataset, trace_statistics

    sets = [xr.load_dataset(path) for path in args.converged]
    sets.sort(key=lambda d: str(d.attrs.get("design_trace")) != "logarithmic")
    traces = [str(d.attrs.get("design_trace")) for d in sets]
    if traces[0] != "logarithmic" or traces[1] == "logarithmic":
        raise CommandError(f"--converged: fronts of {' and '.join(traces)}; give the "
                           f"logarithmic trace's and one other's")
    objectives = [d.attrs["objectives"] for d in sets]
    if objectives[0] != objectives[1]:
        raise CommandError(f"--converged: the searches' objectives differ ({objectives[0]!r} "
                           f"against {objectives[1]!r})")
    stats = checked(lambda: trace_statistics(seed_sets(sets[0]), seed_sets(sets[1]),
                                             objectives[0].split()))
    ds = trace_fronts_dataset(stats, *sets, {"history": command_line()})
    write_dataset(ds, args.out)
    hv = ds["hypervolume_median"].values
    eps = ds["epsilon_additive"].values
    return [f"hypervolume median {traces[0]} {hv[0]:.4g}, {traces[1]} {hv[1]:.4g}; A12 "
            f"{float(ds['a12']):.3g} (Mann-Whitney p {float(ds['mann_whitney_p']):.3g}); "
            f"epsilon {eps[0]:.3g} / {eps[1]:.3g}: {ds.attrs['verdict_text']}"
            + (" (indicative)" if ds.attrs["indicative"] else ""), f"-> {args.out}"]
