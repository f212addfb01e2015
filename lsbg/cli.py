"""Command line interface: ``lsbg <subcommand> ...``.

Every subcommand is a function ``add_<name>_parser(subparsers)`` that adds its
parser and sets ``handler=<function(args) -> exit code>`` as a default. They
are listed in :data:`PARSERS`, either as the function itself or as a
``"module:function"`` string imported when the parser is built. To add a
subcommand (e.g. ``simulate``), write, in its own module::

    from lsbg import cli

    def add_simulate_parser(subparsers):
        parser = subparsers.add_parser("simulate", help="...")
        cli.add_design_options(parser)       # the same design options as geometry
        parser.set_defaults(handler=run_simulate)

and add ``"lsbg.<module>:add_simulate_parser"`` to :data:`PARSERS`. Keep heavy
imports inside the handler, so that ``lsbg --help`` stays fast. Handlers may
raise :class:`lsbg.design.DesignError` (or :class:`CommandError`): :func:`main`
prints the message on stderr and returns exit code 2.

Exit codes: 0 success; 2 bad input (argparse usage errors raise
``SystemExit(2)``, design errors return 2).
"""

from __future__ import annotations

import argparse
import importlib
import logging
import math
import sys

from lsbg import __version__
from lsbg.design import BASE_CONE_RULES, CONFIG_KEYS, HANDS, TRACES, DesignError, GearPairDesign

__all__ = ["main", "build_parser", "add_design_options", "design_from_args", "CommandError",
           "PARSERS", "add_geometry_parser"]


class CommandError(ValueError):
    """Bad command-line input that is not a design parameter (exit code 2)."""


# What each design key means; the unit comes from the key's suffix.
_DESCRIPTIONS = {
    "pinion_teeth": "number of pinion teeth z1",
    "gear_teeth": "number of gear teeth z2",
    "module_mm": "outer transverse module m",
    "shaft_angle_deg": "shaft angle Sigma",
    "normal_pressure_angle_deg": "normal pressure angle at the mean point",
    "spiral_angle_deg": "mean spiral angle on the pitch cone",
    "pinion_hand": "hand of spiral of the pinion",
    "addendum_mm": "outer addendum",
    "dedendum_mm": "outer dedendum",
    "trace": "tooth trace: logarithmic (LSBG) or circular (SBG)",
    "face_width_mm": "face width along the pitch cone generator",
    "cutter_radius_mm": "radius of the circular cutter arc (SBG)",
    "base_cone_rule": "base cone rule: involute (20 deg normal pressure angle) or paper (Eq. 6)",
    "backlash_mm": "circumferential backlash on the mean pitch circle",
    "density_kg_m3": "density of both gears",
    "pinion_bore_mm": "pinion bore diameter",
    "gear_bore_mm": "gear bore diameter",
}
_UNITS = {"_mm": "mm", "_deg": "deg", "_kg_m3": "kg/m^3"}
_CHOICES = {"trace": TRACES, "base_cone_rule": BASE_CONE_RULES, "pinion_hand": HANDS}
# Short spellings used in the paper's workflow, besides --<key>.
_ALIASES = {"spiral_angle_deg": ("--spiral-angle",)}


def _unit(key):
    for suffix, unit in _UNITS.items():
        if key.endswith(suffix):
            return unit
    return None


def add_design_options(parser):
    """Add ``--design FILE.yaml`` and one option per design parameter.

    Options are generated from :data:`lsbg.design.CONFIG_KEYS` (``module_mm``
    -> ``--module-mm``), in the paper's units; each defaults to ``None`` so
    that :func:`design_from_args` can tell what was given.

    Parameters
    ----------
    parser : argparse.ArgumentParser
    """
    paper = GearPairDesign().to_config()
    group = parser.add_argument_group(
        "design parameters (paper units; they override --design; defaults: the paper's "
        "Table 1 and lsbg.design.GearPairDesign)")
    group.add_argument("--design", metavar="FILE.yaml",
                       help="YAML file with design keys as in lsbg.design.CONFIG_KEYS")
    for key in CONFIG_KEYS:
        unit = _unit(key)
        value = paper[key]
        shown = f"{value:g}" if isinstance(value, float) else value
        description = _DESCRIPTIONS.get(key, key.replace("_", " "))
        units = f" [{unit}]" if unit else ""
        kwargs = dict(dest=key, default=None, help=f"{description}{units} (default: {shown})")
        if key in _CHOICES:
            kwargs["choices"] = _CHOICES[key]
        elif isinstance(value, int) and not isinstance(value, bool):
            kwargs["type"] = int
            kwargs["metavar"] = "N"
        elif isinstance(value, float):
            kwargs["type"] = float
        if unit:
            kwargs["metavar"] = unit.upper().replace("/", "_").replace("^", "")
        flags = _ALIASES.get(key, ()) + ("--" + key.replace("_", "-"),)
        group.add_argument(*flags, **kwargs)


def _read_yaml(path):
    import yaml

    try:
        with open(path, encoding="utf-8") as handle:
            data = yaml.safe_load(handle)
    except OSError as error:
        raise CommandError(f"--design {path}: {error.strerror}") from None
    except yaml.YAMLError as error:
        raise CommandError(f"--design {path}: not valid YAML ({error})") from None
    if data is None:
        return {}
    if not isinstance(data, dict):
        raise CommandError(f"--design {path}: must hold a mapping of design keys")
    return data


def design_from_args(args) -> GearPairDesign:
    """The design from ``--design`` (if any) overridden by the design options.

    Parameters
    ----------
    args : argparse.Namespace
        Parsed by a parser with :func:`add_design_options`.

    Returns
    -------
    GearPairDesign

    Raises
    ------
    DesignError
        Unknown key in the YAML file or an invalid value; the message names the key.
    CommandError
        The YAML file cannot be read.
    """
    config = _read_yaml(args.design) if getattr(args, "design", None) else {}
    for key in CONFIG_KEYS:
        value = getattr(args, key, None)
        if value is not None:
            config[key] = value
    return GearPairDesign.from_config(config)


# --------------------------------------------------------------- geometry
def add_geometry_parser(subparsers):
    """``lsbg geometry``: design.json, flanks, meshes, URDF and picture of one design."""
    parser = subparsers.add_parser(
        "geometry", help="write the geometry of one design point",
        description="Write design.json, flanks.nc, pinion/gear STL and OBJ, pair.urdf and "
                    "pair.png of one design point into --out (replaced atomically).")
    add_design_options(parser)
    parser.add_argument("--out", required=True, metavar="DIR", help="output directory")
    parser.set_defaults(handler=run_geometry)


def run_geometry(args):
    """Handler of ``lsbg geometry`` [exit code]."""
    from lsbg.export import STAGES, write_geometry

    design = design_from_args(args)
    result = write_geometry(design, args.out)
    times = ", ".join(f"{stage} {result.timings[stage]:.2f}" for stage in STAGES)
    print(f"lsbg geometry: {design.trace}, spiral angle {math.degrees(design.spiral_angle):g} deg "
          f"-> {result.directory} ({times}; total {result.timings['total']:.2f} s)")
    return 0


#: One ``add_<name>_parser(subparsers)`` per subcommand: a function or a
#: ``"module:function"`` string.
PARSERS = [add_geometry_parser]


def build_parser():
    """The ``lsbg`` argument parser with every subcommand of :data:`PARSERS`."""
    parser = argparse.ArgumentParser(
        prog="lsbg", description="Logarithmic spiral bevel gears: geometry, meshing dynamics "
                                 "and statistics (SI inside, paper units at the edges).")
    parser.add_argument("--version", action="version", version=f"lsbg {__version__}")
    parser.add_argument("-v", "--verbose", action="store_true", help="log progress on stderr")
    subparsers = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)
    for add in PARSERS:
        if isinstance(add, str):
            module, _, name = add.partition(":")
            add = getattr(importlib.import_module(module), name)
        add(subparsers)
    for sub in subparsers.choices.values():
        # Also accept -v after the subcommand (SUPPRESS keeps the global value).
        sub.add_argument("-v", "--verbose", action="store_true", default=argparse.SUPPRESS,
                         help="log progress on stderr")
    return parser


def main(argv=None):
    """Run ``lsbg`` with ``argv`` (default ``sys.argv[1:]``).

    Parameters
    ----------
    argv : list of str, optional

    Returns
    -------
    int
        Exit code: 0 on success, 2 on bad input (message on stderr, nothing
        written). Usage errors found by argparse raise ``SystemExit(2)``.
    """
    args = build_parser().parse_args(argv)
    if args.verbose:
        logging.basicConfig(level=logging.INFO, format="%(name)s: %(message)s")
    try:
        return args.handler(args)
    except (DesignError, CommandError) as error:
        print(f"lsbg {args.command}: error: {error}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
