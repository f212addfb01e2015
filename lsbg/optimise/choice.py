"""The choice: one design from a front, by a stated rule.

A Pareto front is a set of equally good compromises; the study needs one
ease-off per gear type. Two rules (:data:`CHOICE_RULES`):

* ``knee`` (the default): normalise each objective over the front's
  feasible non-dominated members to 0..1 (0 its best, 1 its worst value
  there) and take the member with the least sum of normalised objectives:
  the one farthest below the plane through the normalised extremes of the
  front's normalised extremes, sum = 1 (Das, Struct. Optim. 18, 1999,
  characterises the knee by the distance from that plane; Zhang, Tian & Jin,
  IEEE Trans. Evol. Comput. 19, 2015, take the plane of the unit vectors in
  the normalised space, as here). An objective the front does not vary
  counts as 0. Ties go to the first member.
* ``least_transmission_error``: among the members whose ``contact_pressure``
  does not exceed the permissible pressure, the one with the least
  ``transmission_error`` (the loaded TE peak to peak over the load range); if
  none is within the limit, the one with the least pressure. Needs both
  objectives on the front.

Values in the objectives' units (:data:`lsbg.optimise.objectives.QUANTITIES`).
"""

from __future__ import annotations

import numpy as np

__all__ = ["CHOICE_RULES", "knee_point", "least_transmission_error", "choose",
           "modification_of", "chosen_modification"]

#: The rules by name.
CHOICE_RULES = ("knee", "least_transmission_error")


def knee_point(values):
    """Index of the knee of a front: the least sum of objectives normalised over it.

    Parameters
    ----------
    values : array_like, shape (n, m)
        The front's objective values (minimised), n >= 1.

    Returns
    -------
    int
    """
    values = np.asarray(values, float)
    if values.ndim != 2 or values.shape[0] == 0:
        raise ValueError("knee_point: needs a front of at least one member")
    low, high = values.min(axis=0), values.max(axis=0)
    span = np.where(high > low, high - low, 1.0)
    normalised = np.where(high > low, (values - low) / span, 0.0)
    return int(np.argmin(normalised.sum(axis=1)))


def least_transmission_error(transmission_error, pressure, permissible):
    """Index of the least transmission error within a permissible pressure.

    Parameters
    ----------
    transmission_error : array_like, shape (n,)
        [urad].
    pressure : array_like, shape (n,)
        Largest contact pressure of each member [MPa].
    permissible : float
        [MPa].

    Returns
    -------
    int
        The least TE among the members with pressure <= permissible, or the
        least pressure if none.
    """
    te = np.asarray(transmission_error, float)
    pressure = np.asarray(pressure, float)
    within = pressure <= permissible
    if not np.any(within):
        return int(np.argmin(pressure))
    return int(np.flatnonzero(within)[np.argmin(te[within])])


def choose(values, objectives, rule="knee", permissible_pressure=None):
    """Index of the chosen member of a front under a rule.

    Parameters
    ----------
    values : array_like, shape (n, m)
        Objective values of the front's members.
    objectives : sequence of str
        Their names.
    rule : str
        One of :data:`CHOICE_RULES`.
    permissible_pressure : float, optional
        [MPa], for ``least_transmission_error``.

    Returns
    -------
    int

    Raises
    ------
    ValueError
        For an unknown rule, or ``least_transmission_error`` without both of
        its objectives or a permissible pressure.
    """
    objectives = list(objectives)
    values = np.asarray(values, float).reshape(-1, len(objectives))
    if rule == "knee":
        return knee_point(values)
    if rule == "least_transmission_error":
        missing = [n for n in ("transmission_error", "contact_pressure") if n not in objectives]
        if missing or permissible_pressure is None:
            raise ValueError(f"optimise.choice = {rule!r}: needs the objectives "
                             f"transmission_error and contact_pressure and a permissible "
                             f"pressure (missing: {missing or ['permissible pressure']})")
        return least_transmission_error(values[:, objectives.index("transmission_error")],
                                        values[:, objectives.index("contact_pressure")],
                                        permissible_pressure)
    raise ValueError(f"optimise.choice = {rule!r}: one of {CHOICE_RULES}")


def modification_of(dataset, index):
    """The ease-off of one design of a front's dataset (:func:`lsbg.optimise.dataset.front_dataset`).

    Parameters
    ----------
    dataset : xarray.Dataset
        With the ease-off variables per individual (um, the reliefs' lengths as fractions).
    index : int
        The individual.

    Returns
    -------
    lsbg.tca.modification.FlankModification
    """
    from lsbg.optimise.space import VARIABLES
    from lsbg.tca.modification import FlankModification

    values = {}
    for field, *_ in VARIABLES.values():
        variable = dataset[field]
        scale = 1e-6 if variable.attrs.get("units") == "um" else 1.0
        values[field] = float(variable.values[index]) * scale
    return FlankModification(**values)


def chosen_modification(dataset):
    """The chosen design of a front's dataset (:func:`lsbg.optimise.dataset.front_dataset`).

    Parameters
    ----------
    dataset : xarray.Dataset
        With the ease-off variables per individual and the ``chosen`` index.

    Returns
    -------
    lsbg.tca.modification.FlankModification

    Raises
    ------
    ValueError
        If the front has no feasible member (nothing was chosen).
    """
    index = int(dataset.attrs.get("chosen", -1))
    if index < 0:
        raise ValueError("the front has no feasible design: nothing was chosen")
    return modification_of(dataset, index)
