"""The release rule and the preference among released designs, in the objectives' units.

A gear engineer releases a new ease-off only if it is better where it was meant
to be and no worse anywhere else, checked in the model that will be trusted:

* :func:`released`: a candidate is released only if none of the ``criteria``
  is worse than the design it replaces by more than ``tolerance`` (relative)
  and at least one is better by more than ``tolerance``.
* :func:`weighted_order`: among the released, the least weighted sum of the
  differences from the replaced design, each weight per unit of its quantity
  (per µrad, per MPa, per mm, per %): a preference stated once, in engineering
  units, not normalised over whatever candidates a run found.
* two alternative rules, to show where the chosen design ranks under them:
  :func:`lexicographic_order` (the criteria in their order, values within
  ``tolerance`` of the best counted equal) and :func:`knee_order` (each
  quantity normalised over the candidates, the least sum:
  :func:`lsbg.optimise.choice.knee_point`'s rule).

Values are ``{name: array over the candidates}`` in the quantities' own units.
"""

from __future__ import annotations

import numpy as np

__all__ = ["ALTERNATIVE_RULES", "released", "scores", "weighted_order",
           "lexicographic_order", "knee_order", "order", "rank_of"]

#: The rules a chosen design is ranked under besides the weights.
ALTERNATIVE_RULES = ("lexicographic", "knee")


def _column(values, name, count):
    return np.asarray(values[name], float).reshape(count)


def released(values, reference, criteria, tolerance):
    """Which candidates are no worse than the replaced design and better in one criterion.

    Parameters
    ----------
    values : dict
        ``{name: array (n,)}`` of the candidates (minimised quantities).
    reference : dict
        ``{name: float}``, the design they would replace.
    criteria : sequence of str
        The quantities compared.
    tolerance : float
        Relative [-]: worse means above ``reference (1 + tolerance)``, better
        below ``reference (1 - tolerance)``.

    Returns
    -------
    numpy.ndarray of bool, shape (n,)
    """
    criteria = list(criteria)
    count = np.asarray(values[criteria[0]]).size
    no_worse = np.ones(count, bool)
    better = np.zeros(count, bool)
    for name in criteria:
        value, base = _column(values, name, count), float(reference[name])
        no_worse &= value <= base + tolerance * abs(base)
        better |= value < base - tolerance * abs(base)
    return no_worse & better


def scores(values, reference, weights):
    """The weighted sum of each candidate's differences from the replaced design.

    Parameters
    ----------
    values : dict
        ``{name: array (n,)}``.
    reference : dict
        ``{name: float}``.
    weights : dict
        ``{name: weight per unit of the quantity}`` (per µrad, per MPa, ...).

    Returns
    -------
    numpy.ndarray, shape (n,)
        In the weights' common unit (with the default weights, µrad of
        transmission error); below 0 better than the replaced design.
    """
    names = list(weights)
    count = np.asarray(values[names[0]]).size
    return sum(float(w) * (_column(values, n, count) - float(reference[n]))
               for n, w in weights.items())


def weighted_order(values, reference, weights):
    """Candidates' indices from the least :func:`scores` (ties: the first)."""
    return np.argsort(scores(values, reference, weights), kind="stable")


def lexicographic_order(values, criteria, tolerance):
    """Candidates' indices in the criteria's lexicographic order.

    Each place goes to the remaining candidate that is best in the first
    criterion, those within ``tolerance`` (relative) of the best counted
    equal and told apart by the next criterion, and so on; the last
    criterion decides outright.

    Parameters
    ----------
    values : dict
        ``{name: array (n,)}``.
    criteria : sequence of str
    tolerance : float
        [-].

    Returns
    -------
    numpy.ndarray of int
    """
    criteria = list(criteria)
    count = np.asarray(values[criteria[0]]).size
    columns = [_column(values, name, count) for name in criteria]
    left, out = list(range(count)), []
    while left:
        pool = np.array(left)
        for column in columns[:-1]:
            best = column[pool].min()
            pool = pool[column[pool] <= best + tolerance * abs(best)]
        pick = int(pool[np.argmin(columns[-1][pool])])
        out.append(pick)
        left.remove(pick)
    return np.array(out, int)


def knee_order(values, names):
    """Candidates' indices from the least sum of the quantities normalised over them."""
    names = list(names)
    count = np.asarray(values[names[0]]).size
    table = np.column_stack([_column(values, n, count) for n in names])
    low, high = table.min(axis=0), table.max(axis=0)
    normalised = np.where(high > low, (table - low) / np.where(high > low, high - low, 1.0),
                          0.0)
    return np.argsort(normalised.sum(axis=1), kind="stable")


def order(rule, values, reference, weights, criteria, tolerance):
    """Candidates' indices under a rule: ``weights``, ``lexicographic`` or ``knee``.

    Parameters
    ----------
    rule : str
    values, reference, weights, criteria, tolerance
        As :func:`weighted_order`, :func:`lexicographic_order` (the criteria)
        and :func:`knee_order` (the weights' quantities).

    Returns
    -------
    numpy.ndarray of int

    Raises
    ------
    ValueError
        For an unknown rule.
    """
    if rule == "weights":
        return weighted_order(values, reference, weights)
    if rule == "lexicographic":
        return lexicographic_order(values, criteria, tolerance)
    if rule == "knee":
        return knee_order(values, list(weights))
    raise ValueError(f"rule = {rule!r}: one of weights, {', '.join(ALTERNATIVE_RULES)}")


def rank_of(index, ordering):
    """The place (1 the first) of candidate ``index`` in an ordering, 0 if absent."""
    where = np.flatnonzero(np.asarray(ordering) == index)
    return int(where[0]) + 1 if where.size else 0
