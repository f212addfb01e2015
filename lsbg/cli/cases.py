"""The sensitivity cases of a command (``--case``), read over the configuration's sections.

Apart from :mod:`lsbg.cli.options` so that only the commands that compute
cases depend on :mod:`lsbg.experiments.sensitivity` (their handlers call
:func:`sensitivity_cases`; :func:`lsbg.study.stages.function_closure`).
"""

from __future__ import annotations

from lsbg.cli.options import CommandError, check_output, contact_of, flank_sections_of

__all__ = ["sensitivity_cases"]


def sensitivity_cases(args, stage, template, option="--case-out", model="line"):
    """The sensitivity cases of ``--case`` over the configuration, checked before any work.

    Parameters
    ----------
    args : argparse.Namespace
        With ``case`` and the resolved ``settings``.
    stage : str
        ``"dynamics"``, ``"contact_state"`` or ``"fe_ltca"``: a case whose key
        does not reach it is an error.
    template : str or None
        The output template with ``{case}``.
    option : str
        The option that gave it (``--case-out``; ``lsbg sensitivity``: ``--out``).
    model : str
        The contact model of the cases (the line model).

    Returns
    -------
    list of tuple
        ``(name, contact parameters, real flanks, output path)`` per case.

    Raises
    ------
    CommandError
        Naming the ``--case`` text, or the template.
    """
    import yaml

    from lsbg.contact import ContactParameters
    from lsbg.experiments.sensitivity import CASE_STAGES, case_sections, study_cases
    from lsbg.files import fill_template
    from lsbg.tca.separation import RealFlanks

    if not args.case:
        return []
    if not template:
        raise CommandError(f"--case: needs {option}, a file template with {{case}}")
    base = contact_of(args.settings, model=model).to_config()
    modification, misalignment = flank_sections_of(args.settings)
    cases = []
    for text in args.case:
        key, sep, value = text.partition("=")
        key = key.strip()
        try:
            if key in CASE_STAGES and stage not in CASE_STAGES[key]:
                raise ValueError(f"a {key} case does not change this analysis")
            expanded = study_cases({key: [yaml.safe_load(value) if sep else None]},
                                   args.settings["misalignment_map"])
            for name, (key, factor) in expanded.items():
                contact, flank_mod, flank_mis = case_sections(key, factor, base, modification,
                                                              misalignment)
                cases.append((name, ContactParameters.from_config(contact),
                              RealFlanks.from_config(flank_mod, flank_mis),
                              fill_template(template, option, case=name)))
        except (ValueError, TypeError, KeyError) as err:
            raise CommandError(f"--case {text!r}: {err}") from None
    paths = [path for *_, path in cases]
    if len(set(paths)) < len(paths):
        raise CommandError(f"{option} {template!r}: the cases would write the same file; put "
                           f"{{case}} in it")
    for path in paths:
        check_output(path, option)
    return cases
