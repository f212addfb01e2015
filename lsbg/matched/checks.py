"""The ``optimise.matched`` section's checks beyond its schema (at parse time, no analysis)."""

from __future__ import annotations

__all__ = ["matched_problems"]


def matched_problems(config):
    """Every problem of the ``optimise.matched`` section, one line each naming the key and value.

    Parameters
    ----------
    config : dict
        The configuration, the schema's defaults filled in.

    Returns
    -------
    list of str
    """
    section = config.get("optimise", {}).get("matched", {})
    pairs, full_runs = section.get("pairs", 30), section.get("full_runs", 3)
    problems = []
    if isinstance(pairs, int) and isinstance(full_runs, int) and full_runs > pairs:
        problems.append(f"optimise.matched.full_runs = {full_runs!r}: at most "
                        f"optimise.matched.pairs = {pairs!r} "
                        f"(the full runs are of the matched pairs)")
    return problems
