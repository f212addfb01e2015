"""Configuration sections into lsbg's objects, their errors naming the user's key.

A section's table maps each of its keys to ``(object, field, SI value of one
unit of the key)`` (e.g. :data:`lsbg.tooth.config.TOOTH_CONFIG_KEYS`); the
objects (dataclasses) check their own fields and raise a ValueError whose
message starts with the field's name. :func:`section_objects` builds them and
turns such an error into one that starts with the user's key and value
(``tooth.poisson_ratio = 0.5: ...``).
"""

from __future__ import annotations

__all__ = ["config_key", "section_objects"]


def config_key(keys, target, field):
    """The key of a section's table (``key -> (object, field, unit)``) that sets
    ``field`` of ``target``, or None."""
    return next((k for k, (t, f, _) in keys.items() if t == target and f == field), None)


def section_objects(values, classes, named, section):
    """Each object of a configuration section, its errors naming the user's key.

    The objects' own checks raise a ValueError whose message starts with the
    field's name; that message is raised again behind the key and the value
    the user gave.

    Parameters
    ----------
    values : dict
        ``{target: {field: SI value}}``.
    classes : dict
        ``{target: class}``, each built as ``class(**values[target])``.
    named : callable
        ``named(target, field)`` -> ``(key path, value as given)``, or None
        for a field no key sets.
    section : str
        Named in the message of such a field.

    Returns
    -------
    dict
        ``{target: object}``.

    Raises
    ------
    ValueError
        ``<key path> = <value>: <the object's message>``.
    """
    built = {}
    for target, cls in classes.items():
        try:
            built[target] = cls(**values[target])
        except ValueError as err:
            key = named(target, str(err).split(" ", 1)[0])
            if key is None:
                raise ValueError(f"{section}: {err}") from None
            raise ValueError(f"{key[0]} = {key[1]!r}: {err}") from None
    return built
