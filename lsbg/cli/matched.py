"""Matched designs of the two traces' fronts: ``lsbg matched-pairs``."""

from __future__ import annotations

from lsbg.cli.options import CommandError, add_config_options, add_output, checked, command_line

__all__ = ["add_matched_pairs_parser"]

#: The sections ``lsbg matched-pairs`` reads: the searches' (its own, optimise.matched; the
#: line model, the envelope, the rated torque), the runs' (the simulation, the driveline)
#: and the steady state's start.
SECTIONS = ("optimise", "flank_modification", "misalignment", "misalignment_map",
            "tca", "contact", "simulation", "driveline", "rating", "tooth", "limits",
            "statistics")


def add_matched_pairs_parser(subparsers):
    """``lsbg matched-pairs``: the traces' front members matched, each pair answered."""
    parser = subparsers.add_parser(
        "matched-pairs", help="the two traces' front members matched one to one, each pair's "
                              "stability, contact state and FE stresses",
        description="Pair the LSBG's converged front members with the SBG's (--converged, "
                    "lsbg converge-front) on pattern_movement and contact_pressure normalised "
                    "by the common box of --trace-fronts (lsbg trace-fronts): the least total "
                    "distance, pairs beyond optimise.matched.caliper dropped, at most "
                    "optimise.matched.pairs. "
                    "Each design's stability at both boundaries by the proxy (the loaded TE "
                    "through the linearised system) and, for the closest "
                    "optimise.matched.full_runs "
                    "pairs, by full runs (the compiled engine, the line model on the uniform "
                    "bed); its FE figures with --compliance-file at the release's aligned "
                    "positions (--release); Wilcoxon's signed-rank test and a bootstrap "
                    "interval of the log std ratios. Writes --out (NetCDF, CF-1.11).")
    add_config_options(parser, SECTIONS)
    for option, metavar, text in (
            ("--converged", "CONVERGED.nc", "each trace's converged fronts (lsbg converge-front)"),
            ("--geometry", "DIR", "each trace's geometry directory (lsbg geometry)"),
            ("--release", "RELEASE.nc", "each trace's release (lsbg release): its positions"),
            ("--compliance-file", "COMPLIANCE.nc", "each trace's FE compliance (lsbg "
                                                   "compliance)"),
            ("--rating", "RATING.nc", "each trace's ISO 10300 rating at its design point "
                                      "(lsbg rate; it takes no ease-off)")):
        parser.add_argument(option, nargs=2, required=True, metavar=metavar,
                            help=f"{text}, the logarithmic trace's first")
    parser.add_argument("--front", nargs="+", required=True, metavar="FRONT.nc",
                        help="every search's front (lsbg optimise) of both traces: the "
                             "designs' ease-offs")
    parser.add_argument("--trace-fronts", required=True, metavar="TRACE_FRONTS.nc",
                        help="the traces' fronts compared (lsbg trace-fronts): the common box")
    add_output(parser, metavar="MATCHED_PAIRS.nc")
    parser.set_defaults(handler=run_matched_pairs)


def run_matched_pairs(args):
    """Handler of ``lsbg matched-pairs``: its summary lines."""
    import logging

    import xarray as xr

    from lsbg.files import write_dataset
    from lsbg.matched.run import box_of, matched_designs
    from lsbg.matched.stage import answer_pairs

    log = logging.getLogger("lsbg.matched_pairs")
    converged = [xr.load_dataset(p) for p in args.converged]
    traces = [str(d.attrs.get("design_trace")) for d in converged]
    if traces[0] != "logarithmic" or traces[1] == "logarithmic":
        raise CommandError(f"--converged: fronts of {' and '.join(traces)}; give the "
                           f"logarithmic trace's first, then one other's")
    from lsbg.config import ConfigError
    from lsbg.matched.checks import matched_problems

    problems = matched_problems(args.settings)
    if problems:
        raise ConfigError(problems[0])
    section = args.settings["optimise"]["matched"]
    trace_fronts = xr.load_dataset(args.trace_fronts)
    matched = checked(lambda: matched_designs(converged, box_of(trace_fronts),
                                              float(section["caliper"]), int(section["pairs"])))
    fronts = [xr.load_dataset(p) for p in args.front]
    releases = [xr.load_dataset(p) for p in args.release]
    ratings = [xr.load_dataset(p) for p in args.rating]
    ds = answer_pairs(args.settings, args.geometry, releases, args.compliance_file, matched,
                      converged, fronts, log.info, ratings)
    ds.attrs["history"] = command_line()
    write_dataset(ds, args.out)
    a = ds.attrs
    lines = [f"{a['pairs_found']} pairs of {a['candidates']} designs within caliper "
             f"{a['caliper']} ({a['dropped_by_caliper']} of {a['assigned']} assigned dropped; "
             f"{a['pairs_sought']} sought), {a['full_run_pairs']} with full runs"]
    for b, boundary in enumerate(ds["boundary"].values):
        for q, quantity in enumerate(ds["quantity"].values):
            mean, p = (float(ds[f"ratio_{n}"].values[0, b, q]) for n in ("mean", "wilcoxon_p"))
            lines.append(f"{boundary}, {quantity}: mean log std ratio (proxy) {mean:.3g}, "
                         f"Wilcoxon p {p:.3g}")
    return lines + [f"-> {args.out}"]
