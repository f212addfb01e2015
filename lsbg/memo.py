"""Small memos of results that do not depend on what a search varies.

A V-H map asks for the same flank grids at every cell, and an ease-off
search for the same grids, kernel constants and coast-side contacts at every
design: :func:`memoised` keeps the last few results of each kind per
:class:`lsbg.gear.geometry.GearPair` (least recently used first out, so the
memo of a kind never holds more than its ``size``), dropped with the pair.
The key must name everything the value depends on besides the pair; a value
is returned as stored, so a caller that hands out mutable arrays copies
them (:func:`copied`). :func:`per_member` keeps a frozen design's derived
quantities of each member in the design itself.
"""

from __future__ import annotations

import dataclasses
import functools
import weakref

__all__ = ["memoised", "cached", "copied", "float_key", "fields_key", "arrays_key", "per_member",
           "MEMO_SIZE"]

#: Results kept per pair and kind unless the caller says otherwise.
MEMO_SIZE = 16

_MEMOS = weakref.WeakKeyDictionary()


def memoised(pair, kind, key, compute, size=MEMO_SIZE):
    """The value of ``compute()`` for ``key``, computed once per pair and kind.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
        The pair the value belongs to (the memo lives as long as it does).
    kind : str
        What is kept (each kind has its own memo of ``size`` entries).
    key : hashable
        Everything the value depends on besides the pair.
    compute : callable
        ``compute()`` gives the value on a miss.
    size : int
        Entries kept of this kind [-], >= 1.

    Returns
    -------
    object
        The stored value (the same object on every hit).
    """
    return cached(_MEMOS.setdefault(pair, {}).setdefault(kind, {}), key, compute, size)


def cached(memo, key, compute, size):
    """``memo[key]``, computed by ``compute()`` on a miss, in a dict of at most
    ``size`` entries: the least recently used is dropped first.

    Parameters
    ----------
    memo : dict
        The memo, kept by the caller (its order is the order of use).
    key : hashable
    compute : callable
    size : int
        Entries kept [-], >= 1.
    """
    if key in memo:
        memo[key] = value = memo.pop(key)  # most recently used last
        return value
    value = compute()
    while len(memo) >= size:
        memo.pop(next(iter(memo)))
    memo[key] = value
    return value


def copied(arrays):
    """Copies of a tuple of arrays, so that a caller cannot change a memo's."""
    return tuple(a.copy() for a in arrays)


def float_key(values):
    """The exact bits of some floats as a key: 0.0 and -0.0 (equal, but not the
    same input to the arithmetic) are told apart."""
    return tuple(float(v).hex() for v in values)


def fields_key(instance):
    """:func:`float_key` of a dataclass of numbers (its fields in order), such as a
    :class:`lsbg.tca.misalignment.Misalignment`."""
    return float_key(getattr(instance, f.name) for f in dataclasses.fields(instance))


def arrays_key(*arrays):
    """The exact values of some arrays as a key, with their types, shapes and memory
    layouts: numpy's vectorised transcendental functions may round an element
    differently in another layout, so arrays of the same values laid out otherwise
    are other inputs."""
    return tuple((a.dtype.str, a.shape, a.strides, a.tobytes()) for a in arrays)


def per_member(method):
    """Memoise a method of a member (1: pinion, 2: gear) of a frozen design.

    The derived quantities are asked for hundreds of thousands of times in an
    ease-off search; the design's fields never change after it is built, so
    each member's value is computed once, by the method's own expression (the
    same float), and kept in the instance (its derived properties are
    ``functools.cached_property`` for the same reason).
    """
    memo_name = f"_{method.__name__}_memo"

    @functools.wraps(method)
    def memoised_method(self, member):
        memo = self.__dict__.setdefault(memo_name, {})
        if member not in memo:
            memo[member] = method(self, member)
        return memo[member]

    return memoised_method
