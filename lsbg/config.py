"""The study configuration: its schema, its defaults, overrides, and errors that name the key.

One configuration serves the workflow and every ``lsbg`` command: sections of
keys in the paper's units, described, typed and defaulted by one schema,
``lsbg/schemas/config.schema.yaml``, package data (:func:`load_schema`). A command
reads it as the workflow does (:func:`resolve_config`): the schema's defaults,
then each ``--config FILE`` merged over them (:func:`merge_config`, as
``snakemake --configfile`` merges), then each ``--set section.key=value``
(:func:`parse_override`), typed and checked by the schema before any work
(:func:`schema_problems`); every problem is one line that starts with the
key path and the value the user gave (``contact.slices = 0: ...``).

A section's keys become lsbg's objects (dataclasses, SI inside) through
their ``from_config`` constructors; :func:`section_objects` builds several
objects of one section and turns their errors into the user's key and value
(``tooth.poisson_ratio = 0.5: ...``).
"""

from __future__ import annotations

import copy
import functools
import math
import re
from pathlib import Path

__all__ = ["SCHEMA_PATH", "ConfigError", "load_schema", "key_path", "section_values",
           "nonfinite_problems", "schema_problems", "fill_defaults", "section_keys", "merge_config",
           "parse_override", "apply_override", "resolve_config", "config_key",
           "section_objects"]

#: The schema of the study configuration (package data; the workflow validates against it too).
SCHEMA_PATH = Path(__file__).resolve().parent / "schemas" / "config.schema.yaml"


class ConfigError(ValueError):
    """A configuration file or override that the schema refuses (exit code 2 in ``lsbg``)."""


@functools.lru_cache(maxsize=None)
def _schema(path):
    import yaml

    with open(path, encoding="utf-8") as handle:
        # libyaml's loader where PyYAML has it: every lsbg command reads the schema
        return yaml.load(handle, Loader=getattr(yaml, "CSafeLoader", yaml.SafeLoader))


def load_schema(path=SCHEMA_PATH):
    """The configuration schema, loaded (a fresh copy).

    Parameters
    ----------
    path : str or pathlib.Path
        Default: :data:`SCHEMA_PATH`.

    Returns
    -------
    dict
    """
    if not Path(path).is_file():
        raise ConfigError(f"{path}: no configuration schema there (lsbg's own is "
                          f"{SCHEMA_PATH})")
    return copy.deepcopy(_schema(str(path)))


def key_path(parts):
    """``["sweep", "spiral_angles_deg", 2]`` -> ``"sweep.spiral_angles_deg[2]"``."""
    text = ""
    for part in parts:
        text += f"[{part}]" if isinstance(part, int) else (f".{part}" if text else str(part))
    return text or "(top level)"


def section_values(config, section):
    """Every key the user set in a section, with its value (``design (design.x = 1, ...)``):
    the key part of a problem no single key is at fault for (lsbg cannot compute the
    numbers together)."""
    values = ", ".join(f"{section}.{key} = {value!r}" for key, value in config[section].items())
    return f"{section} ({values})"


def nonfinite_problems(config, where=()):
    """NaN and infinite numbers anywhere in ``config``, one line each.

    Parameters
    ----------
    config : dict or list or scalar
    where : tuple
        Key path of ``config`` itself.

    Returns
    -------
    list of str
    """
    if isinstance(config, dict):
        return [p for key, value in config.items()
                for p in nonfinite_problems(value, (*where, key))]
    if isinstance(config, list):
        return [p for k, value in enumerate(config)
                for p in nonfinite_problems(value, (*where, k))]
    if isinstance(config, float) and not math.isfinite(config):
        return [f"{key_path(where)} = {config!r}: must be a finite number"]
    return []


#: A number YAML 1.1 reads as text: an exponent without a decimal point (1e-6).
_NUMBER_TEXT = re.compile(r"^[-+]?(\d+\.?\d*|\.\d+)[eE][-+]?\d+$")


def schema_problems(config, schema):
    """Every violation of the schema, one line each, starting with the key path.

    Parameters
    ----------
    config : dict
    schema : dict
        :func:`load_schema`.

    Returns
    -------
    list of str
    """
    import jsonschema

    problems = []
    for error in jsonschema.Draft202012Validator(schema).iter_errors(config):
        where = list(error.absolute_path)
        if error.validator == "additionalProperties":
            known = sorted(error.schema.get("properties", {}))
            problems += [f"{key_path(where + [key])}: unknown key (known: {', '.join(known)})"
                         for key in sorted(set(error.instance) - set(known))]
        elif error.validator == "required":
            problems += [f"{key_path(where + [key])}: missing (a required key)"
                         for key in error.validator_value if key not in error.instance]
        else:
            hint = ""
            if (error.validator == "type" and isinstance(error.instance, str)
                    and _NUMBER_TEXT.match(error.instance)):
                hint = (f" (YAML reads {error.instance} as text: write the mantissa with a "
                        f"decimal point, e.g. 1.0e-6)")
            problems.append(f"{key_path(where)}: {error.message}{hint}")
    return sorted(problems)


def fill_defaults(config, schema):
    """Fill in the schema's ``default`` of every missing key, in place.

    The same as ``snakemake.utils.validate(config, schema, set_default=True)``
    for this schema (objects nested in ``properties`` only): a section left
    out takes its default (e.g. ``{}``), whose own keys then take theirs.

    Parameters
    ----------
    config : dict
        Valid under ``schema``.
    schema : dict
    """
    for key, subschema in schema.get("properties", {}).items():
        if key not in config and "default" in subschema:
            # a copy: the schema's default objects must not be filled in themselves
            config[key] = copy.deepcopy(subschema["default"])
        if isinstance(config.get(key), dict):
            fill_defaults(config[key], subschema)


def section_keys(schema, section):
    """``[(key, description, default)]`` of a section of the schema, in its order.

    Parameters
    ----------
    schema : dict
    section : str

    Returns
    -------
    list of tuple
        The default is the schema's, or None where it has none.
    """
    properties = schema.get("properties", {}).get(section, {}).get("properties", {})
    return [(key, " ".join(str(spec.get("description", "")).split()), spec.get("default"))
            for key, spec in properties.items()]


def merge_config(base, update):
    """``update`` merged into ``base`` key by key, as Snakemake merges config files.

    Parameters
    ----------
    base, update : dict

    Returns
    -------
    dict
        A new mapping: nested mappings merged, any other value replaced.
    """
    merged = dict(base)
    for key, value in update.items():
        if isinstance(value, dict) and isinstance(merged.get(key), dict):
            merged[key] = merge_config(merged[key], value)
        else:
            merged[key] = value
    return merged


def _key_schema(schema, parts):
    """The schema of the key at ``parts``, or None where the schema has no such key."""
    node = schema
    for part in parts:
        properties = node.get("properties")
        if properties is None or part not in properties:
            return None
        node = properties[part]
    return node


def _accepts(subschema, kind):
    kinds = subschema.get("type", [])
    return kind in ([kinds] if isinstance(kinds, str) else kinds)


def parse_override(text, schema):
    """``section.key=value`` -> (key path, value), the value typed by the key's schema.

    The value is read as YAML (``0.5``, ``[E, P]``, ``null``, ``fe``); a key
    whose schema takes a number also takes ``1e-6`` (which YAML 1.1 reads as
    text).

    Parameters
    ----------
    text : str
        As given to ``--set``.
    schema : dict

    Returns
    -------
    (list of str, object)

    Raises
    ------
    ConfigError
        One line naming the text: no ``=``, or a key the schema does not have
        (with the keys it has there).
    """
    import yaml

    path, sep, raw = text.partition("=")
    parts = [p.strip() for p in path.split(".")]
    if not sep or not all(parts):
        raise ConfigError(f"--set {text!r}: must be section.key=value (e.g. "
                          f"contact.model=line)")
    for depth in range(1, len(parts) + 1):
        if _key_schema(schema, parts[:depth]) is None:
            parent = _key_schema(schema, parts[:depth - 1]) or {}
            known = ", ".join(sorted(parent.get("properties", {}))) or "none"
            raise ConfigError(f"--set {text!r}: {key_path(parts[:depth])}: unknown key "
                              f"(known: {known})")
    subschema = _key_schema(schema, parts)
    try:
        value = yaml.safe_load(raw)
    except yaml.YAMLError:
        value = raw
    if isinstance(value, str) and _NUMBER_TEXT.match(value) and _accepts(subschema, "number"):
        value = float(value)
    return parts, value


def apply_override(config, parts, value):
    """Set the key at ``parts`` of ``config`` to ``value`` (sections created), in place."""
    node = config
    for part in parts[:-1]:
        if not isinstance(node.get(part), dict):
            node[part] = {}
        node = node[part]
    node[parts[-1]] = value


def resolve_config(files=(), overrides=(), schema=None, read=None):
    """A command's configuration: the schema's defaults, the files, then the overrides.

    Parameters
    ----------
    files : sequence of str or pathlib.Path
        Configuration files, merged in order (:func:`merge_config`).
    overrides : sequence of str
        ``section.key=value`` texts (:func:`parse_override`), applied in order.
    schema : dict, optional
        Default :func:`load_schema`.
    read : callable, optional
        ``read(path)`` -> mapping; default: YAML refusing duplicate keys
        (:func:`lsbg.files.load_yaml`).

    Returns
    -------
    dict
        Every section of the schema, its keys' defaults filled in where they
        have one.

    Raises
    ------
    ConfigError
        One line per problem, each naming the key path and value (or the
        file), before any work.
    """
    from lsbg.files import read_yaml_file

    schema = load_schema() if schema is None else schema
    read = read or read_yaml_file
    config = {}
    for path in files:
        config = merge_config(config, read(path))
    for text in overrides:
        parts, value = parse_override(text, schema)
        apply_override(config, parts, value)
    # a command reads sections, not a study: no key is required of it
    checked = _without_required(schema)
    problems = nonfinite_problems(config) + schema_problems(config, checked)
    if problems:
        raise ConfigError("; ".join(problems))
    # every section a command may read, its keys' defaults filled in
    for key, subschema in schema.get("properties", {}).items():
        if "properties" in subschema:
            config.setdefault(key, {})
    fill_defaults(config, schema)
    return config


def _without_required(schema):
    """The schema without its ``required`` lists (at every level)."""
    if isinstance(schema, dict):
        return {k: _without_required(v) for k, v in schema.items() if k != "required"}
    if isinstance(schema, list):
        return [_without_required(v) for v in schema]
    return schema


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
