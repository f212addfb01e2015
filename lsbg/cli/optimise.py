"""Each gear type at its best ease-off: ``lsbg optimise``."""

from __future__ import annotations

from lsbg.cli.options import (add_config_options, add_geometry_input, add_output, checked,
                              command_line)

__all__ = ["add_optimise_parser"]

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
    from lsbg.files import write_text_atomically
    from lsbg.optimise.choice import chosen_modification
    from lsbg.study.params import yaml_text

    trace = ds.attrs["design_trace"]
    if ds.attrs["chosen"] < 0:
        section = dict(settings["flank_modification"])
        comment = f"{trace}: no feasible design in the front; the shared ease-off stands"
    else:
        section = chosen_modification(ds).to_config()
        comment = (f"{trace}: the ease-off lsbg optimise chose ({ds.attrs['choice_rule']}, "
                   f"seed {ds.attrs['seed']})")
    section = {k: v for k, v in section.items() if v is not None}
    text = yaml_text({"flank_modification": section}, comment)
    write_text_atomically(path, text)
    return f"its ease-off as an overlay -> {path}"
