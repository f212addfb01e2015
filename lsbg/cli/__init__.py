"""Command line interface: ``lsbg <subcommand> ...``.

One module per group of subcommands, in the order the data flows:
:mod:`lsbg.cli.geometry` (``geometry``, ``points``), :mod:`lsbg.cli.simulate`
(``simulate``, ``sensitivity``, ``convergence``), :mod:`lsbg.cli.speed`
(``mesh-mode``, ``speed-run``, ``speed-curve``), :mod:`lsbg.cli.analysis`
(``ltca``, ``combine``, ``summary``, ``report``), :mod:`lsbg.cli.contact_state`
(``tca``, ``misalignment-map``), :mod:`lsbg.cli.tooth` (``compliance``, and the
options of the tooth's own compliance); the options they share are in
:mod:`lsbg.cli.options`.

Every subcommand is a function ``add_<name>_parser(subparsers)`` that adds its
parser and sets ``handler=<function(args) -> exit code>`` as a default. They
are listed in :data:`PARSERS` as ``"module:function"`` strings, imported when
the parser is built. To add a subcommand, write, in its own module::

    from lsbg.cli.options import add_design_options

    def add_wear_parser(subparsers):
        parser = subparsers.add_parser("wear", help="...")
        add_design_options(parser)       # the same design options as geometry
        parser.set_defaults(handler=run_wear)

and add ``"lsbg.<module>:add_wear_parser"`` to :data:`PARSERS`. Keep heavy
imports inside the handler, so that ``lsbg --help`` stays fast. Handlers
check their outputs before the work starts
(:func:`lsbg.cli.options.check_output`). A user's mistake is one of
:data:`USER_ERRORS`: a bad design value (:class:`lsbg.gear.design.DesignError`), a
bad option (:class:`CommandError`), a missing, wrong, corrupt or changed input
file (:class:`lsbg.files.InputError`, raised by lsbg.files and lsbg.dynamics.dataset);
:func:`main` prints its one-line message on stderr, without a traceback, and
returns exit code 2. Any other exception is a bug and keeps its traceback.

Exit codes: 0 success; 2 bad input (argparse usage errors raise
``SystemExit(2)``, the errors of :data:`USER_ERRORS` return 2); 3 a
simulation blew up.
"""

from __future__ import annotations

import argparse
import importlib
import logging
import sys

from lsbg import __version__
from lsbg.cli.options import CommandError, add_design_options, design_from_args
from lsbg.gear.design import DesignError
from lsbg.files import InputError

__all__ = ["main", "build_parser", "add_design_options", "design_from_args", "CommandError",
           "PARSERS", "USER_ERRORS"]

#: Exceptions that are a user's mistake: exit code 2 with the message, no traceback.
USER_ERRORS = (DesignError, CommandError, InputError)

#: One ``add_<name>_parser(subparsers)`` per subcommand, as ``"module:function"``.
PARSERS = [
    "lsbg.cli.config:add_check_config_parser",
    "lsbg.cli.geometry:add_geometry_parser",
    "lsbg.cli.geometry:add_points_parser",
    "lsbg.cli.simulate:add_simulate_parser",
    "lsbg.cli.simulate:add_sensitivity_parser",
    "lsbg.cli.simulate:add_convergence_parser",
    "lsbg.cli.analysis:add_ltca_parser",
    "lsbg.cli.tooth:add_compliance_parser",
    "lsbg.cli.rating:add_rate_parser",
    "lsbg.cli.contact_state:add_tca_parser",
    "lsbg.cli.contact_state:add_misalignment_map_parser",
    "lsbg.cli.speed:add_mesh_mode_parser",
    "lsbg.cli.speed:add_speed_run_parser",
    "lsbg.cli.speed:add_speed_curve_parser",
    "lsbg.cli.sweep:add_sweep_run_parser",
    "lsbg.cli.sweep:add_sweep_combine_parser",
    "lsbg.cli.analysis:add_combine_parser",
    "lsbg.cli.analysis:add_summary_parser",
    "lsbg.cli.analysis:add_report_parser",
]


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
        Exit code: 0 on success, 2 on bad input (one line on stderr, nothing
        written), or the handler's (3: a simulation blew up). Usage errors
        found by argparse raise ``SystemExit(2)``.
    """
    args = build_parser().parse_args(argv)
    if args.verbose:
        logging.basicConfig(level=logging.INFO, format="%(name)s: %(message)s")
    try:
        return args.handler(args)
    except USER_ERRORS as error:
        print(f"lsbg {args.command}: error: {error}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
