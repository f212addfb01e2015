"""Model-form sensitivity at the paper's design point: cases that scale or switch one setting.

The line model rests on settings nobody measured for this pair: the line
stiffness (calibrated to ISO 6336-1's c_gamma), the mesh-mode damping ratio
and the number of slices; the flanks carry a crowning of the practice's usual
amount; the pair runs aligned. A sensitivity case changes one of them (the
workflow's ``sensitivity`` section) and reruns both traces at the paper's
design point; the paper report asks whether each claim's verdict survives
every case.

* a **scale** case multiplies a contact setting by a factor
  (``mesh_damping_ratio: [0.5, 2]``), or the pinion's ease-off
  (``crowning: [0, 0.5, 2]``: lengthwise and profile crowning and bias
  together; 0 gives the conjugate flanks);
* a **switch** case sets a word-valued setting: ``compliance: [fe]`` runs the
  line model on the tooth's own stiffness from finite elements (or, from a
  study under ``compliance: fe``, ``[uniform]`` on the uniform bed), and
  ``displacement: [envelope]`` becomes one case per corner of the assembly's
  displacement envelope (``misalignment_map.axes`` at +-``range``, added to the
  ``misalignment`` section), named ``displaced_E+0.1_P-0.1``;
* an **operating** case runs the pair at another operating point: ``pinion_speed:
  [0.25, 1.5]`` multiplies the pinion's speed (the ``simulation`` section's); its
  stability is a cell of claim 1, but the rating (claim 3) stays at the study's
  speed, so it rates no case of this kind (:func:`rated_cases`);
* a **boundary** case switches the run's boundary (``simulation.boundary``):
  ``boundary: [driveline]`` runs the mesh inside the torsional driveline
  (:mod:`lsbg.dynamics.driveline`) instead of the paper's prescribed pinion speed, at
  the study's speed (its K_v is rated).

Which stages a case reaches (:data:`CASE_STAGES`): every case reruns the
dynamics (an operating or a boundary case only the dynamics); crowning and the line
stiffness also change the V-H map (the
contact state), crowning also the FE loaded TCA (the teeth's stresses).
"""

from __future__ import annotations

from lsbg.files import number_label

__all__ = ["SENSITIVITY_KEYS", "FLANK_KEYS", "SENSITIVITY_SWITCHES", "OPERATING_KEYS",
           "CASE_STAGES", "SIMULATION_SWITCHES", "CASE_KEYS", "case_name", "parse_case",
           "scaled_contact", "case_label", "study_cases", "case_sections", "case_simulation",
           "stage_cases", "rated_cases", "pair_case_keys", "pair_cases"]

#: Contact keys (paper units) a case may scale.
SENSITIVITY_KEYS = ("mesh_damping_ratio", "line_stiffness_N_per_mm_um", "slices")

#: Scale keys of the flanks -> the flank_modification keys the factor multiplies.
FLANK_KEYS = {"crowning": ("lengthwise_crowning_um", "profile_crowning_um", "bias_um")}

#: Scale keys of the operating point -> the ``simulation`` key the factor multiplies.
OPERATING_KEYS = {"pinion_speed": "pinion_speed_deg_s"}

#: Word-valued keys a case may switch -> their values.
SENSITIVITY_SWITCHES = {"compliance": ("uniform", "fe"), "displacement": ("envelope",),
                        "boundary": ("prescribed_pinion", "driveline")}

#: Switches of the ``simulation`` section (the others switch the contact's).
SIMULATION_SWITCHES = ("boundary",)

#: The stages a case's key reaches: "dynamics" (the line-model runs),
#: "contact_state" (the V-H map), "fe_ltca" (the FE loaded TCA).
CASE_STAGES = {"mesh_damping_ratio": ("dynamics",),
               "line_stiffness_N_per_mm_um": ("dynamics", "contact_state"),
               "slices": ("dynamics",),
               "compliance": ("dynamics",),
               "crowning": ("dynamics", "contact_state", "fe_ltca"),
               "displacement": ("dynamics",),
               "pinion_speed": ("dynamics",),
               "boundary": ("dynamics",)}

#: Every key of the ``sensitivity`` section.
CASE_KEYS = tuple(CASE_STAGES)

#: A corner case's name starts so; its value is the corner's label.
_DISPLACED = "displaced"

#: Words of the keys and values in the reports.
_LABELS = {"mesh_damping_ratio": "damping ratio", "line_stiffness_N_per_mm_um": "line stiffness",
           "slices": "slices", "compliance": "compliance", "fe": "FE", "uniform": "uniform",
           "crowning": "crowning", "pinion_speed": "pinion speed",
           "boundary": "boundary", "driveline": "torsional driveline",
           "prescribed_pinion": "prescribed pinion speed"}


def case_name(key, factor):
    """Name of a case: ``mesh_damping_ratio_x0.5``, ``crowning_x2``, ``compliance_fe``, or
    ``displaced_E+0.1_P-0.1`` for a corner of the displacement envelope.

    Parameters
    ----------
    key : str
        One of :data:`SENSITIVITY_KEYS`, :data:`FLANK_KEYS`, :data:`OPERATING_KEYS` or
        :data:`SENSITIVITY_SWITCHES`.
    factor : float or str
        [-]; a switch's value; for ``displacement`` a corner's label
        (``"E+0.1 P-0.1"``, :func:`lsbg.tca.misalignment.envelope_corners`).
    """
    if key == "displacement":
        return f"{_DISPLACED}_{str(factor).replace(' ', '_')}"
    if key in SENSITIVITY_SWITCHES:
        return f"{key}_{factor}"
    return f"{key}_x{number_label(factor)}"


def case_label(name):
    """A case name in words: ``damping ratio ×0.5``, ``compliance: FE``, ``conjugate
    flanks (crowning ×0)``, ``displaced E+0.1 P-0.1``.

    Parameters
    ----------
    name : str
        As :func:`case_name` gives it.
    """
    key, value = parse_case(name)
    if key == "displacement":
        return f"displaced {value} mm"
    if key in SENSITIVITY_SWITCHES:
        return f"{_LABELS[key]}: {_LABELS.get(value, value)}"
    if key in FLANK_KEYS and value == 0:
        return "conjugate flanks (crowning ×0)"
    return f"{_LABELS.get(key, key)} ×{number_label(value)}"


def parse_case(name):
    """``(key, factor)`` of a case name (:func:`case_name`); ``(key, value)`` of a switch;
    ``("displacement", corner label)`` of a corner.

    Raises
    ------
    ValueError
        If the name is none of :func:`case_name`'s forms.
    """
    name = str(name)
    if name.startswith(f"{_DISPLACED}_"):
        return "displacement", name[len(_DISPLACED) + 1:].replace("_", " ")
    for key, values in SENSITIVITY_SWITCHES.items():
        head, _, value = name.rpartition("_")
        if head == key and value in values:
            return key, value
    key, sep, factor = name.rpartition("_x")
    try:
        value = float(factor)
    except ValueError:
        value = None
    scales = (*SENSITIVITY_KEYS, *FLANK_KEYS, *OPERATING_KEYS)
    if not sep or key not in scales or value is None:
        raise ValueError(f"case {name!r}: must be KEY_xFACTOR with KEY one of "
                         f"{', '.join(scales)}, "
                         f"{', '.join(f'{k}_{v}' for k, vs in SENSITIVITY_SWITCHES.items() for v in vs if k != 'displacement')}"
                         f" or {_DISPLACED}_CORNER")
    return key, value


def _check_factor(key, factor, least=0.0, strict=True):
    if (not isinstance(factor, (int, float)) or isinstance(factor, bool)
            or not (factor > least if strict else factor >= least)):
        rule = "a positive number" if strict else "a number >= 0"
        raise ValueError(f"sensitivity.{key} factor {factor!r}: must be {rule}")


def _check_switch(key, value):
    values = SENSITIVITY_SWITCHES[key]
    if value not in values:
        raise ValueError(f"sensitivity.{key} value {value!r}: must be one of {values}")


def scaled_contact(contact, key, factor):
    """The contact setting of a case: ``{key: contact[key] * factor}``, or
    ``{key: value}`` for a switch; ``{}`` for a case of the flanks.

    Parameters
    ----------
    contact : dict
        The ``contact`` section (paper units).
    key : str
        One of :data:`SENSITIVITY_KEYS`, :data:`FLANK_KEYS` or
        :data:`SENSITIVITY_SWITCHES`.
    factor : float or str
        [-], > 0; a switch's value.

    Returns
    -------
    dict
        At most one key; ``slices`` rounded to a whole number.

    Raises
    ------
    ValueError
        Naming the key or the factor.
    """
    if key in FLANK_KEYS or key == "displacement":
        return {}
    if key in OPERATING_KEYS:
        _check_factor(key, factor)
        return {}
    if key in SENSITIVITY_SWITCHES:
        _check_switch(key, factor)
        # (a switch of the simulation section leaves the contact as it is)
        return {} if key in SIMULATION_SWITCHES else {key: factor}
    if key not in SENSITIVITY_KEYS:
        keys = (*SENSITIVITY_KEYS, *FLANK_KEYS, *OPERATING_KEYS, *SENSITIVITY_SWITCHES)
        raise ValueError(f"sensitivity key {key!r}: must be one of {', '.join(keys)}")
    _check_factor(key, factor)
    value = contact[key] * factor
    return {key: int(round(value)) if key == "slices" else value}


def study_cases(section, misalignment_map=None):
    """Every case of a ``sensitivity`` section, the envelope expanded to its corners.

    Parameters
    ----------
    section : dict
        ``{key: [factor or value, ...]}``.
    misalignment_map : dict, optional
        The ``misalignment_map`` section (its ``axes`` and ``range`` [mm; deg
        for Sigma] give the corners of ``displacement: [envelope]``; default
        E and P at +-0.1).

    Returns
    -------
    dict
        ``{case name: (key, factor or value)}`` in the section's order; a
        corner's value is its label (``"E+0.1 P-0.1"``).

    Raises
    ------
    ValueError
        A key or value :func:`scaled_contact` refuses, or a negative crowning factor.
    """
    from lsbg.tca.misalignment import envelope_corners

    vh = misalignment_map or {}
    out = {}
    for key, values in section.items():
        for value in values:
            if key == "displacement":
                _check_switch(key, value)
                for corner in envelope_corners(vh.get("axes") or ["E", "P"],
                                               vh.get("range") or 0.1):
                    out[case_name(key, corner)] = (key, corner)
            else:
                if key in FLANK_KEYS:
                    _check_factor(key, value, strict=False)
                else:
                    scaled_contact({k: 1.0 for k in SENSITIVITY_KEYS}, key, value)
                out[case_name(key, value)] = (key, value)
    return out


def stage_cases(cases, stage):
    """The cases of :func:`study_cases` that reach ``stage`` (:data:`CASE_STAGES`).

    Parameters
    ----------
    cases : dict
        ``{name: (key, value)}``.
    stage : str
        ``"dynamics"``, ``"contact_state"`` or ``"fe_ltca"``.
    """
    return {name: kv for name, kv in cases.items() if stage in CASE_STAGES[kv[0]]}


def rated_cases(cases):
    """The cases of :func:`study_cases` whose run's dynamic factor the rating takes: all but
    the operating cases (the rating holds at the study's own operating point).

    Parameters
    ----------
    cases : iterable of str or dict
        Case names (a dict: its keys).

    Returns
    -------
    list of str
        In the given order.
    """
    return [name for name in cases if parse_case(name)[0] not in OPERATING_KEYS]


def case_simulation(key, value, simulation):
    """The ``simulation`` section of a case (paper units): the operating cases' own.

    Parameters
    ----------
    key, value
        The case's key and its factor, switch value or corner label, as
        :func:`case_sections` takes them.
    simulation : dict
        The study's ``simulation`` section.

    Returns
    -------
    dict
        A new dictionary; the given one is left alone.
    """
    if key in OPERATING_KEYS:
        _check_factor(key, value)
        name = OPERATING_KEYS[key]
        return {**simulation, name: simulation[name] * value}
    if key in SIMULATION_SWITCHES:
        _check_switch(key, value)
        return {**simulation, key: value}
    return dict(simulation)


def pair_case_keys(config):
    """The sensitivity keys whose cases also run on the practice and best pairs.

    Parameters
    ----------
    config : dict
        The configuration: ``practice.sensitivity`` (``["all"]`` or a list of keys
        of the ``sensitivity`` section).

    Returns
    -------
    tuple of str
        In the ``sensitivity`` section's order.

    Raises
    ------
    ValueError
        Naming ``practice.sensitivity`` and the key that is none of the section's.
    """
    chosen = list(config["practice"].get("sensitivity", ["all"]))
    if chosen == ["all"]:
        return tuple(config["sensitivity"])
    for k, key in enumerate(chosen):
        if key not in CASE_KEYS:
            raise ValueError(f"practice.sensitivity[{k}] = {key!r}: must be a key of the "
                             f"sensitivity section ({', '.join(CASE_KEYS)}), or the list be "
                             f"[all]")
    return tuple(key for key in config["sensitivity"] if key in chosen)


def pair_cases(cases, keys):
    """The cases of :func:`study_cases` whose key is one of ``keys`` (:func:`pair_case_keys`).

    Parameters
    ----------
    cases : dict
        ``{name: (key, value)}``.
    keys : iterable of str
        Keys of the ``sensitivity`` section.
    """
    keys = set(keys)
    return {name: kv for name, kv in cases.items() if kv[0] in keys}


def case_sections(key, value, contact, modification, misalignment):
    """The ``contact``, ``flank_modification`` and ``misalignment`` sections of a case.

    Parameters
    ----------
    key : str
        A case's key (:func:`parse_case`).
    value : float or str
        Its factor, switch value or corner label.
    contact, modification, misalignment : dict
        The study's sections (paper units).

    Returns
    -------
    tuple of dict
        New dictionaries; the given ones are left alone.
    """
    from lsbg.tca.misalignment import DISPLACEMENTS, corner_displacements

    contact = {**contact, **scaled_contact(contact, key, value)}
    modification, misalignment = dict(modification), dict(misalignment)
    if key in FLANK_KEYS:
        _check_factor(key, value, strict=False)
        for name in FLANK_KEYS[key]:
            modification[name] = modification.get(name, 0.0) * value
    elif key == "displacement":
        for letter, shift in corner_displacements(value).items():
            config_key = DISPLACEMENTS[letter][1]
            misalignment[config_key] = misalignment.get(config_key, 0.0) + shift
    return contact, modification, misalignment
