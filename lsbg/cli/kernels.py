"""``lsbg kernels``: compile lsbg's kernels into numba's cache before the jobs that call them.

The workflow's first job (rule ``kernels``, :mod:`lsbg.study.kernels`): from an
empty cache the sweep's jobs would each compile the same kernels at the same
time. It writes a record of what it compiled or loaded, and how long it took.
"""

from __future__ import annotations

from lsbg.cli.options import (
    add_config_options,
    add_output,
    command_line,
    contact_of,
    design_of,
    flanks_of,
    simulation_of,
)

__all__ = ["add_kernels_parser"]

#: The sections ``lsbg kernels`` reads: the small case is the study's design point.
KERNELS_SECTIONS = ("design", "contact", "simulation", "flank_modification", "misalignment")


def add_kernels_parser(subparsers):
    """``lsbg kernels``: compile the kernels of a design point into numba's cache."""
    parser = subparsers.add_parser(
        "kernels", help="compile the kernels of a design point into numba's cache",
        description="Run every compiled kernel of a design point once on a small case of "
                    "the configured design and flanks (the geometry's picture, the loaded "
                    "and unloaded TCA, 4 ms of both contact models with the compiled engine, "
                    "the block bootstrap), so that numba's cache holds them: compiled from "
                    "an empty cache, loaded from a warm one. Writes a JSON record: the "
                    "cache's version, the seconds it took and the kernels called.")
    add_config_options(parser, KERNELS_SECTIONS)
    add_output(parser, metavar="KERNELS.json", help="output JSON record")
    parser.set_defaults(handler=run_kernels)


def run_kernels(args):
    """Handler of ``lsbg kernels``: one summary line."""
    import json

    from lsbg.files import write_text_atomically
    from lsbg.numba_cache import compiled_sources_tag
    from lsbg.study.kernels import compile_kernels

    settings = args.settings
    record = compile_kernels(design_of(settings), flanks_of(settings),
                             contact_of(settings, model="point"),
                             contact_of(settings, model="line"),
                             simulation_of(settings, "compiled"))
    record = {"numba_cache": compiled_sources_tag(), "seconds": round(record["seconds"], 3),
              "kernels": record["kernels"], "history": command_line()}
    text = json.dumps(record, indent=1) + "\n"
    write_text_atomically(args.out, text)
    return [f"{len(record['kernels'])} kernels ready in {record['numba_cache']} "
            f"({record['seconds']:.1f} s) -> {args.out}"]
