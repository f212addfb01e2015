"""Each gear type at its best ease-off: ``lsbg optimise``, ``lsbg release``; trace against
trace: ``lsbg converge-front``, ``lsbg trace-fronts``."""

from __future__ import annotations

from lsbg.cli.options import (CommandError, add_config_options, add_geometry_input, add_output,
                              checked, command_line)

__all__ = ["add_optimise_parser", "add_release_parser", "add_converge_front_parser",
           "add_trace_fronts_parser"]

#: The sections ``lsbg optimise`` reads: its own, the shared design, the envelope,
#: the marking compound, the line model, the pinion's speed, the rating (rated
#: torque, lubricant, permissible pressure), the steel and the budget's limit.
SECTIONS = ("optimise", "flank_modification", "misalignment", "misalignment_map", "tca",
            "contact", "simulation", "rating", "tooth", "limits")


def add_optimise_parser(subparsers):
    """``lsbg optimise``: the Pareto front of a design point's ease-off and its chosen design."""
    parser = subparsers.add_parser(
        "optimise", help="multi-objective ease-off optimisation of a design point",
        description="Search the pinion's ease-off coefficients within optimise.bounds with "
                    "NSGA-II (optimise.population x optimise.generations designs, "
                    "optimise.seed) for the objectives optimise.objectives (loaded TE over "
                    "the load range, the bearing pattern's movement over the "
                    "misalignment_map envelope, the largest contact pressure, the mesh "
                    "loss), under the constraints of no edge contact, the pattern inside "
                    "the face, the relief within the backlash and contact kept; pick one "
                    "design by optimise.choice; write the final population, the front (every "
                    "feasible design evaluated that no other dominates), "
                    "the chosen design, the hypervolume by generation and the shared "
                    "design's figures (the flank_modification section) to --out (NetCDF, "
                    "CF-1.11). Everything is checked before the first evaluation.")
    add_geometry_input(parser)
    add_config_options(parser, SECTIONS)
    add_output(parser, metavar="FRONT.nc")
    add_output(parser, option="--overlay-out", metavar="OVERLAY.yaml", required=False,
               help="also write the chosen design as a configuration overlay (its "
                    "flank_modification section; the shared one where nothing was chosen), "
                    "to be given as a further --config")
    parser.set_defaults(handler=run_optimise)


def run_optimise(args):
    """Handler of ``lsbg optimise``: its summary lines."""
    import logging

    from lsbg.files import write_dataset
    from lsbg.gear.geometry import GearPair
    from lsbg.optimise.checks import run_settings
    from lsbg.optimise.run import optimise_pair
    from lsbg.solid.directory import read_design

    design = read_design(args.geometry)
    settings = checked(lambda: run_settings(args.settings, design))
    log = logging.getLogger("lsbg.optimise")
    ds = optimise_pair(GearPair(design), settings, log=log.info)
    ds.attrs["history"] = command_line()
    write_dataset(ds, args.out)
    a = ds.attrs
    lines = [f"{design.trace}: {a['evaluations']} designs in {a['run_seconds']:.3g} s "
             f"(seed {a['seed']}), {a['population_feasible_individuals']} of the last "
             f"{a['population']} feasible, {a['front_individuals']} on the front, hypervolume "
             f"{a['final_hypervolume']:.4g}"]
    if a["chosen"] < 0:
        lines.append("no feasible design: none chosen")
    else:
        k = a["chosen"]
        shown = ", ".join(f"{name} {ds[name].values[k]:.4g} {ds[name].attrs['units']} "
                          f"(shared {float(ds[f'reference_{name}']):.4g})"
                          for name in a["objectives"].split())
        relief = ", ".join(f"{name} {ds[name].values[k]:.3g}" for name in (
            "lengthwise_crowning", "profile_crowning", "bias", "spiral_angle_correction",
            "pressure_angle_correction", "pinion_tip_relief", "gear_tip_relief"))
        among = (", among the designs below the shared TE at the rated torque"
                 if a.get("chosen_below_shared_transmission_error") else "")
        lines.append(f"chosen ({a['choice_rule']}{among}): {relief} um; {shown}")
    lines.append(f"-> {args.out}")
    if args.overlay_out:
        lines.append(_write_overlay(ds, args.settings, args.overlay_out))
    return lines


def _write_overlay(ds, settings, path):
    """The chosen design's ``flank_modification`` section -> ``path`` (YAML); its line."""
    from lsbg.optimise.choice import chosen_modification

    trace = ds.attrs["design_trace"]
    if ds.attrs["chosen"] < 0:
        return _overlay(None, settings, path, f"{trace}: no feasible design in the front; "
                                              f"the shared ease-off stands")
    return _overlay(chosen_modification(ds), settings, path,
                    f"{trace}: the ease-off lsbg optimise chose ({ds.attrs['choice_rule']}, "
                    f"seed {ds.attrs['seed']})")


def _overlay(modification, settings, path, comment):
    """A ``flank_modification`` overlay -> ``path`` (YAML; None: the configuration's own,
    the shared design); its line."""
    from lsbg.files import write_text_atomically
    from lsbg.study.params import yaml_text

    section = (dict(settings["flank_modification"]) if modification is None
               else modification.to_config())
    section = {k: v for k, v in section.items() if v is not None}
    text = yaml_text({"flank_modification": section}, comment)
    write_text_atomically(path, text)
    return f"its ease-off as an overlay -> {path}"


def _add_front_inputs(parser):
    """``--geometry``, the configuration's options and ``--front`` (one per seed)."""
    add_geometry_input(parser)
    add_config_options(parser, SECTIONS)
    parser.add_argument("--front", nargs="+", required=True, metavar="FRONT.nc",
                        help="the fronts of the trace's searches (lsbg optimise), one per seed")


def add_release_parser(subparsers):
    """``lsbg release``: the fronts' candidates under the verdict's models, one released."""
    parser = subparsers.add_parser(
        "release", help="release an ease-off of the fronts, or keep the shared one",
        description="Re-evaluate the candidates of the fronts (lsbg optimise, --front, one "
                    "per seed) and the shared design (flank_modification) at mesh positions "
                    "doubled from optimise.phases until every figure changes by less than "
                    "optimise.release.convergence, first on the uniform bed, then the best "
                    "optimise.release.fe_candidates of each front with the FE loaded TCA "
                    "(--compliance-file) over the load range, aligned and at the corners of "
                    "the misalignment_map envelope; release the candidate that is no worse "
                    "than the shared design in every optimise.release.criteria (within "
                    "optimise.release.tolerance), better in one, and least by "
                    "optimise.release.weights; else keep the shared design. Writes the "
                    "candidates under every model to --out (NetCDF, CF-1.11) and the "
                    "released ease-off as an overlay to --overlay-out.")
    _add_front_inputs(parser)
    parser.add_argument("--compliance-file", required=True, metavar="COMPLIANCE.nc",
                        help="the design point's FE compliance (lsbg compliance): read if it "
                             "holds these inputs, else computed and written there")
    add_output(parser, metavar="RELEASE.nc")
    add_output(parser, option="--overlay-out", metavar="OVERLAY.yaml",
               help="the released ease-off (the shared one where none is released) as a "
                    "configuration overlay, to be given as a further --config")
    parser.set_defaults(handler=run_release)


def run_release(args):
    """Handler of ``lsbg release``: its summary lines."""
    import logging

    import xarray as xr

    from lsbg.cli.options import fe_compliance_of
    from lsbg.files import write_dataset
    from lsbg.gear.geometry import GearPair
    from lsbg.optimise.checks import run_settings
    from lsbg.optimise.release import (ReleaseSettings, release_dataset, release_design,
                                       released_modification)
    from lsbg.optimise.verdict import evaluator_factory
    from lsbg.solid.directory import read_design

    design = read_design(args.geometry)
    settings = checked(lambda: run_settings(args.settings, design))
    release = checked(lambda: ReleaseSettings.from_config(
        args.settings["optimise"].get("release", {})))
    fronts = [xr.load_dataset(path) for path in args.front]
    traces = {str(f.attrs.get("design_trace")) for f in fronts}
    if traces != {design.trace}:
        raise CommandError(f"--front: fronts of {', '.join(sorted(traces))}, not of the "
                           f"geometry's {design.trace}")
    compliance, _ = fe_compliance_of(args)
    evaluator_at = evaluator_factory(GearPair(design), settings["evaluation"])

    log = logging.getLogger("lsbg.release")
    result = release_design(evaluator_at, settings, release, fronts, compliance, log.info)
    ds = release_dataset(result, release, {
        "history": command_line(),
        **{f"reference_flank_modification_{k}": ("" if v is None else v)
           for k, v in settings["reference"].to_config().items()},
        **{f"design_{k}": v for k, v in design.to_config().items()}})
    write_dataset(ds, args.out)
    a, k = ds.attrs, int(ds.attrs["chosen"])
    lines = [f"{design.trace}: {ds.sizes['candidate']} candidates of {len(fronts)} fronts, "
             f"uniform bed at {a['uniform_positions']} positions, FE at "
             f"{a['fe_aligned_positions']} (aligned) and {a['fe_corners_positions']} (corners; "
             f"{a['fe_candidates_evaluated']} candidates), {a['released_candidates']} released, "
             f"{a['run_seconds']:.3g} s"]
    shown = ", ".join(f"{name} {float(ds[f'reference_fe_{name}']):.4g}"
                      + ("" if k < 0 else f" -> {float(ds[f'fe_{name}'].values[k]):.4g}")
                      for name in release.criteria)
    if k < 0:
        lines.append(f"none released: the shared ease-off stays (FE: {shown})")
    else:
        lines.append(f"released candidate {k} (seed {int(ds['front_seed'].values[k])}): FE "
                     f"{shown}")
    modification = released_modification(ds)
    comment = (f"{design.trace}: no candidate released (lsbg release); the shared ease-off "
               f"stays" if modification is None else
               f"{design.trace}: the ease-off lsbg release released (seed "
               f"{int(ds['front_seed'].values[k])})")
    lines += [f"-> {args.out}", _overlay(modification, args.settings, args.overlay_out, comment)]
    return lines


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
    _add_front_inputs(parser)
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
