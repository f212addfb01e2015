"""Command line interface: ``lsbg <subcommand> ...``.

One module per group of subcommands, in the order the data flows:
:mod:`lsbg.cli.geometry` (``geometry``, ``points``), :mod:`lsbg.cli.simulate`
(``simulate``, ``sensitivity``, ``convergence``), :mod:`lsbg.cli.speed`
(``mesh-mode``, ``speed-run``, ``speed-curve``), :mod:`lsbg.cli.analysis`
(``ltca``, ``combine``, ``summary``, ``report``), :mod:`lsbg.cli.contact_state`
(``tca``, ``misalignment-map``), :mod:`lsbg.cli.tooth` (``compliance``),
:mod:`lsbg.cli.rating` (``rate``), :mod:`lsbg.cli.sweep` (``sweep-run``,
``sweep-combine``), :mod:`lsbg.cli.config` (``check-config``); what they share
is in :mod:`lsbg.cli.options`.

Every value of the study is set one way: ``--config FILE`` and ``--set
section.key=value`` (:func:`lsbg.cli.options.add_config_options`), checked by
the configuration's schema before any work; a command's own options are only
its inputs, its outputs and what it runs.

Every subcommand is a function ``add_<name>_parser(subparsers)`` that adds its
parser and sets ``handler=<function(args)>`` as a default; :func:`parser_adders`
finds them in the modules of this package (their ``__all__``) when the parser
is built. To add a subcommand, write a new module here::

    from lsbg.cli.options import add_config_options, add_output, settings_of

    def add_wear_parser(subparsers):
        parser = subparsers.add_parser("wear", help="...")
        add_config_options(parser, ("design", "contact"))
        add_output(parser)
        parser.set_defaults(handler=run_wear)

    def run_wear(args):
        from lsbg.wear import wear_dataset      # the stage, imported by the handler
        ...
        return f"wear {...} -> {args.out}"

and list ``add_wear_parser`` in its ``__all__``: nothing else to edit (a module
imports only :mod:`lsbg.cli.options` at its top, since every command builds
the whole parser; tests/study/test_stages.py checks it). Keep the stage's
imports inside the handler: the workflow reruns a command's jobs when a
source its handler reaches changes (:func:`lsbg.study.stages.function_closure`
from :func:`handler_of`), and ``lsbg --help`` stays fast.

:func:`main` runs every handler the same way: the configuration resolved and
checked, the outputs of :func:`lsbg.cli.options.add_output` checked, then the
handler; what it returns (a line, or lines) is printed. A user's mistake is one
of :data:`USER_ERRORS`: a bad configuration key or value
(:class:`lsbg.config.ConfigError`), a bad design value
(:class:`lsbg.gear.design.DesignError`), a bad option
(:class:`~lsbg.cli.options.CommandError`), a missing, wrong, corrupt or changed
input file (:class:`lsbg.files.InputError`); its one-line message goes to
stderr without a traceback, exit code 2. A simulation that blows up
(:class:`lsbg.dynamics.SimulationError`) is exit code 3 with its diagnostic;
any other exception is a bug and keeps its traceback.

Exit codes: 0 success; 2 bad input; 3 a simulation blew up.
"""

from __future__ import annotations

import argparse
import functools
import importlib
import logging
import sys

from lsbg import __version__

__all__ = ["main", "build_parser", "parser_adders", "handler_of", "command_parsers",
           "CommandError", "USER_ERRORS"]


def _user_errors():
    """The exceptions that are a user's mistake: exit code 2 with the message, no
    traceback."""
    from lsbg.cli.options import CommandError
    from lsbg.config import ConfigError
    from lsbg.files import InputError
    from lsbg.gear.design import DesignError

    return (ConfigError, DesignError, CommandError, InputError)


def __getattr__(name):
    """``USER_ERRORS`` (:func:`_user_errors`) and ``CommandError``, imported when first
    asked for: the ``lsbg`` command that a job server serves imports nothing but the
    server's client (:func:`main`), about 0.08 s less at each of a study's jobs."""
    if name == "USER_ERRORS":
        return _user_errors()
    if name == "CommandError":
        from lsbg.cli.options import CommandError

        return CommandError
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")

#: The modules' places in ``lsbg --help`` (the data flow); a module not named comes after.
RANKS = {"config": 0, "geometry": 1, "simulate": 2, "analysis": 3, "tooth": 4, "rating": 5,
         "contact_state": 6, "speed": 7, "sweep": 8, "checks": 9}


def parser_adders():
    """Every ``add_<name>_parser(subparsers)`` of the modules of lsbg.cli, in ``RANKS`` order
    (each module's in its ``__all__`` order).

    A new subcommand is a new module here: found, not registered, so that adding one
    changes no file that the other commands run (their jobs do not rerun).

    Returns
    -------
    list of callable
    """
    import pkgutil

    names = sorted((m.name for m in pkgutil.iter_modules(__path__)),
                   key=lambda name: (RANKS.get(name, len(RANKS)), name))
    adders = []
    for name in names:
        module = importlib.import_module(f"{__name__}.{name}")
        adders += [getattr(module, f) for f in getattr(module, "__all__", ())
                   if f.startswith("add_") and f.endswith("_parser")]
    return adders


def build_parser():
    """The ``lsbg`` argument parser with every subcommand of :data:`PARSERS`."""
    # (no abbreviations: an old option's prefix must not pass as another, --compliance
    # for --compliance-file)
    parser = argparse.ArgumentParser(
        prog="lsbg", allow_abbrev=False, description="Logarithmic spiral bevel gears: geometry, meshing dynamics "
                                 "and statistics (SI inside, paper units at the edges).")
    parser.add_argument("--version", action="version", version=f"lsbg {__version__}")
    parser.add_argument("-v", "--verbose", action="store_true", help="log progress on stderr")
    subparsers = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)
    for add in parser_adders():
        add(subparsers)
    for sub in subparsers.choices.values():
        sub.allow_abbrev = False
        # Also accept -v after the subcommand (SUPPRESS keeps the global value).
        sub.add_argument("-v", "--verbose", action="store_true", default=argparse.SUPPRESS,
                         help="log progress on stderr")
    return parser


@functools.lru_cache(maxsize=None)
def command_parsers():
    """``{command: its argparse parser}`` of every ``lsbg`` subcommand, built once per
    process (the workflow's rules read their options from them)."""
    parser = build_parser()
    return next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction)).choices


def handler_of(command):
    """The function ``lsbg <command>`` runs (its stage's entry point).

    Parameters
    ----------
    command : str
        A subcommand (``"ltca"``).

    Returns
    -------
    callable

    Raises
    ------
    ValueError
        Naming the known subcommands.
    """
    choices = command_parsers()
    if command not in choices:
        raise ValueError(f"lsbg {command}: no such subcommand (known: {', '.join(choices)})")
    return choices[command].get_default("handler")


def run_handler(args):
    """Run a parsed command: configuration and outputs checked first, then the handler.

    Returns
    -------
    int
        The exit code (0; the handler may return another).
    """
    from lsbg.cli.options import check_outputs, settings_of

    if hasattr(args, "overrides"):
        settings_of(args)
    check_outputs(args)
    result = args.handler(args)
    if isinstance(result, int):
        return result
    for line in [result] if isinstance(result, str) else (result or ()):
        print(f"lsbg {args.command}: {line}")
    return 0


def main(argv=None):
    """Run ``lsbg`` with ``argv`` (default ``sys.argv[1:]``).

    Parameters
    ----------
    argv : list of str, optional

    Returns
    -------
    int
        Exit code: 0 on success, 2 on bad input (one line on stderr, nothing
        written), 3 when a simulation blew up. Usage errors found by argparse
        raise ``SystemExit(2)``.
    """
    if argv is None:
        # the `lsbg` command under a local Snakemake run: a process forked from the
        # workflow's job server runs the job, if it serves it (lsbg.cli.job_server)
        from lsbg.cli.job_server import run_on_server

        served = run_on_server(sys.argv[1:])
        if served is not None:
            return served
    from lsbg.cli import options

    options._ARGUMENTS = list(sys.argv[1:] if argv is None else argv)  # the provenance's
    args = build_parser().parse_args(argv)
    if args.verbose:
        logging.basicConfig(level=logging.INFO, format="%(name)s: %(message)s")
    try:
        return run_handler(args)
    except _user_errors() as error:
        print(f"lsbg {args.command}: error: {error}", file=sys.stderr)
        return 2
    except Exception as error:
        # a blow-up: the dynamics' own error (never imported, never raised)
        settings = sys.modules.get("lsbg.dynamics.settings")
        if settings is None or not isinstance(error, settings.SimulationError):
            raise
        print(f"lsbg {args.command}: simulation stopped: {error}", file=sys.stderr)
        return 3


if __name__ == "__main__":
    sys.exit(main())
