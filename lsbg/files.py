"""lsbg's files on disk: atomic writes, checked NetCDF and YAML reading, the user's input errors.

Writers of lsbg put their output beside the target under a temporary name
made from the target's (:func:`temporary_beside`) and rename it at the end
(:func:`write_atomically`); :func:`remove_stale_temporaries` removes what an
interrupted writer left. Readers raise :class:`InputError`, one line naming
the file and how to regenerate it, for a missing, wrong or corrupt input
(:func:`open_dataset`); YAML is read refusing a key given twice
(:func:`load_yaml`). A design point's geometry directory and its manifest are
:mod:`lsbg.solid.directory`; a run's dataset is :mod:`lsbg.dynamics.dataset`.
"""

from __future__ import annotations

import functools
import hashlib
import os
import re
import shutil
import tempfile
import textwrap
from pathlib import Path

__all__ = ["InputError", "InputFileNotFoundError", "file_digest", "kept_file_digest",
           "number_label", "label_clashes", "fill_template", "temporary_beside",
           "remove_stale_temporaries", "write_atomically", "write_dataset", "complete_attributes",
           "VARIABLE_ATTRIBUTES", "as_path_list",
           "open_dataset", "short_labels", "load_yaml", "DuplicateKeyError",
           "duplicate_key_problems", "read_yaml_file"]


class InputError(ValueError):
    """An input file or directory is missing, of the wrong kind, corrupt, or changed
    since lsbg wrote it.

    The message is one line naming the path and, where lsbg wrote it, how to
    regenerate it. The command line reports it with exit code 2.
    """

class InputFileNotFoundError(InputError, FileNotFoundError):
    """An input path that does not exist (also a :class:`FileNotFoundError`)."""

# ------------------------------------------------------------------ hashes
def file_digest(path) -> str:
    """SHA-256 of a file's bytes, as 64 hex digits."""
    with open(path, "rb") as handle:
        return hashlib.file_digest(handle, "sha256").hexdigest()


def kept_file_digest(path) -> str:
    """:func:`file_digest`, read once per process while the file's size and modification
    time stay the same (sources hashed at every Snakemake start and numba cache lookup).

    Parameters
    ----------
    path : str or pathlib.Path
        The file.

    Returns
    -------
    str
        SHA-256 of its bytes, 64 hex digits.
    """
    stat = os.stat(path)
    return _kept_file_digest(os.fspath(path), stat.st_mtime_ns, stat.st_size)


@functools.lru_cache(maxsize=None)
def _kept_file_digest(path, mtime_ns, size):
    return file_digest(path)

# ------------------------------------------------------------- temporaries
#: Suffixes of temporaries: a file being written (``part``), a directory
#: being written (``tmp``), a replaced directory being removed (``old``).
TEMPORARY_SUFFIXES = ("part", "tmp", "old")

def temporary_beside(target, suffix, directory=False) -> Path:
    """Create an empty temporary file or directory ``.<name>.<random>.<suffix>`` beside ``target``.

    Parameters
    ----------
    target : pathlib.Path
        The final path; its folder must exist.
    suffix : str
        One of :data:`TEMPORARY_SUFFIXES`.
    directory : bool
        A directory rather than a file.

    Returns
    -------
    pathlib.Path
        With the permissions of an ordinary new file or directory (the umask's),
        not the private ones of :mod:`tempfile`, since it becomes the output.
    """
    if suffix not in TEMPORARY_SUFFIXES:
        raise ValueError(f"suffix = {suffix!r}: must be one of {TEMPORARY_SUFFIXES}")
    options = dict(prefix=f".{target.name}.", suffix=f".{suffix}", dir=target.parent)
    if directory:
        path = Path(tempfile.mkdtemp(**options))
    else:
        handle, name = tempfile.mkstemp(**options)
        os.close(handle)
        path = Path(name)
    umask = os.umask(0)
    os.umask(umask)
    path.chmod((0o777 if directory else 0o666) & ~umask)
    return path

def remove_stale_temporaries(target) -> list:
    """Remove the temporaries of ``target`` (:func:`temporary_beside`) left by a killed writer.

    The writer of a target calls this before it starts. Snakemake never runs
    two jobs for the same output at once, so every temporary of the target
    that exists then is a dead writer's. (Two lsbg processes writing the same
    target by hand: one may remove the other's temporary, which then fails;
    the target is never half-written.)

    Parameters
    ----------
    target : str or os.PathLike

    Returns
    -------
    list of pathlib.Path
        What was removed.
    """
    target = Path(target)
    # tempfile's random part has no dots, so another target's temporaries never match
    pattern = re.compile(rf"^\.{re.escape(target.name)}\.[A-Za-z0-9_]+\."
                         rf"({'|'.join(TEMPORARY_SUFFIXES)})$")
    if not target.parent.is_dir():
        return []
    removed = []
    for path in sorted(target.parent.iterdir()):
        if pattern.match(path.name):
            if path.is_dir() and not path.is_symlink():
                shutil.rmtree(path, ignore_errors=True)
            else:
                path.unlink(missing_ok=True)
            removed.append(path)
    return removed


def write_atomically(path, write):
    """Write a file through a temporary file beside it, renamed at the end.

    A failure (or an interrupt) leaves neither a half-written ``path`` nor the
    temporary file behind; the temporaries of ``path`` that a killed writer
    left (``.<name>.<random>.part``, :func:`lsbg.files.temporary_beside`) are
    removed before writing. The previous ``path`` stays until the new one is
    complete.

    Parameters
    ----------
    path : str or pathlib.Path
        Target file; its folder is created if needed.
    write : callable
        ``write(tmp_path)`` writes the content to the temporary path (a str).

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    remove_stale_temporaries(path)
    tmp = temporary_beside(path, "part")
    try:
        write(str(tmp))
        os.replace(tmp, path)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise
    return path


def write_text_atomically(path, text):
    """Write ``text`` (UTF-8) to ``path`` through :func:`write_atomically`.

    Parameters
    ----------
    path : str or pathlib.Path
    text : str

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    return write_atomically(path, lambda tmp: Path(tmp).write_text(text, encoding="utf-8"))


def write_dataset(ds, path):
    """Write a dataset to NetCDF atomically (see :func:`write_atomically`).

    Data variables on ``time_full`` (the full-rate record) are compressed
    (zlib level 1, lossless). Every numeric array carries a Fletcher-32
    checksum, so that reading a corrupted file fails (:func:`open_dataset`)
    instead of returning wrong numbers; it costs about 13 % of the size. Long labels are
    shortened (:func:`short_labels`) and every variable gets ``units`` and ``long_name``
    (:func:`complete_attributes`, which refuses one it cannot label).

    Parameters
    ----------
    ds : xarray.Dataset
    path : str or pathlib.Path

    Raises
    ------
    ValueError
        A variable without ``units`` or ``long_name`` (:func:`complete_attributes`).
    """
    encoding = {}
    for name, var in ds.variables.items():
        # HDF5 checksums chunked storage only: not scalars, empty arrays or strings
        if var.dtype.kind in "fiu" and var.ndim and var.size:
            encoding[name] = {"fletcher32": True}
            if name in ds.data_vars and "time_full" in var.dims:
                encoding[name].update(zlib=True, complevel=1, shuffle=True)
    complete_attributes(short_labels(ds))
    write_atomically(path, lambda tmp: ds.to_netcdf(tmp, engine="netcdf4", encoding=encoding))


#: ``units`` and ``long_name`` of the variables and coordinates that their writers leave
#: without them (labels and counters: units "1"; None: the writer gives the units).
VARIABLE_ATTRIBUTES = {
    "axis": ("1", "displacement axis (E, P, G or Sigma)"),
    "case": ("1", "sensitivity case"),
    "contact_model": ("1", "contact model"),
    "contact_tooth": ("1", "contact tooth"),
    "corner": ("1", "corner of the displacement envelope"),
    "edge": ("1", "edge of the active flank"),
    "edge_contact": ("1", "edge contact (1: touched)"),
    "fillet_side_gear": ("1", "gear fillet side (0 drive, 1 coast)"),
    "fillet_side_pinion": ("1", "pinion fillet side (0 drive, 1 coast)"),
    "gear_type": ("1", "gear type"),
    "generation": ("1", "generation"),
    "individual": ("1", "individual"),
    "member": ("1", "gear member"),
    "order": ("1", "mesh harmonic order"),
    "mesh_phase": ("1", "mesh phase (fraction of a base pitch)"),
    "side": ("1", "flank side"),
    "tooth_offset": ("1", "tooth offset from the loaded pair"),
    "tooth_pair": ("1", "tooth pair"),
    "trace": ("1", "tooth trace"),
    "xyz": ("1", "mesh frame axis"),
    "cone_distance": (None, "cone distance"),
    "fillet_cone_distance_gear": (None, "cone distance of a gear fillet point"),
    "fillet_cone_distance_pinion": (None, "cone distance of a pinion fillet point"),
    "mesh_stiffness": (None, "mesh stiffness"),
    "pressure_profile_angle": (None, "profile angle of a pressure sample"),
    "profile_angle": (None, "profile angle"),
    "transmission_error": (None, "transmission error"),
}


def complete_attributes(ds):
    """Give every variable and coordinate ``units`` and ``long_name`` (CF-1.11), in place.

    What a writer left out comes from :data:`VARIABLE_ATTRIBUTES`; a variable still
    without either is refused, so that no file of lsbg has an unlabelled array.

    Parameters
    ----------
    ds : xarray.Dataset

    Returns
    -------
    xarray.Dataset
        ``ds``.

    Raises
    ------
    ValueError
        Naming the variables that lack ``units`` or ``long_name``.
    """
    lacking = []
    for name, variable in ds.variables.items():
        units, long_name = VARIABLE_ATTRIBUTES.get(str(name), (None, None))
        for key, value in (("units", units), ("long_name", long_name)):
            if key not in variable.attrs and value is not None:
                variable.attrs[key] = value
        if not {"units", "long_name"} <= set(variable.attrs):
            lacking.append(str(name))
    if lacking:
        raise ValueError(f"variables without units or long_name: {', '.join(lacking)} "
                         f"(give both, or add them to lsbg.files.VARIABLE_ATTRIBUTES)")
    return ds


#: The longest ``long_name`` of a variable [characters]: xarray's plots take it as the
#: axis label.
LABEL_WIDTH = 40


def short_labels(ds, width=LABEL_WIDTH):
    """Short ``long_name`` labels: a longer one moves to ``description``, in place.

    A variable whose ``long_name`` is longer than ``width`` gets its name in words
    (``transmission_error`` -> ``transmission error``) as its label, the full
    definition kept as ``description``; xarray's plots then read
    "transmission error [urad]".

    Parameters
    ----------
    ds : xarray.Dataset
    width : int
        Characters [-].

    Returns
    -------
    xarray.Dataset
        ``ds``.
    """
    for name, variable in ds.variables.items():
        text = variable.attrs.get("long_name")
        if isinstance(text, str) and len(text) > width:
            variable.attrs["description"] = text
            # whole words only: a cut word would read as another (a unit's letter lost)
            words = str(name).replace("_", " ")
            variable.attrs["long_name"] = (textwrap.shorten(words, width, placeholder="")
                                           or words[:width])
    return ds


def as_path_list(value) -> list:
    """A list of paths from a path, a list of paths, or ``""``/``None`` (empty).

    Parameters
    ----------
    value : str, os.PathLike, sequence of them, or None

    Returns
    -------
    list of pathlib.Path
    """
    if value is None or (isinstance(value, str) and not value.strip()):
        return []
    if isinstance(value, (str, Path)):
        return [Path(value)]
    return [Path(v) for v in value if str(v).strip()]


def open_dataset(path, kind, variables, attributes, what):
    """Read a NetCDF file of lsbg into memory, checking what it must hold.

    Parameters
    ----------
    path : str or os.PathLike
    kind : str
        Named in the message for a missing file ("run", "mesh").
    variables, attributes : sequence of str
        Names the dataset must have.
    what : str
        Named in the message for a file that lacks them.

    Returns
    -------
    xarray.Dataset
        Loaded (the file is closed); ``encoding['source']`` is the path.

    Raises
    ------
    lsbg.files.InputError
        In one line naming the file: it does not exist
        (:class:`lsbg.files.InputFileNotFoundError`), is a directory, cannot be
        read, is not NetCDF, is truncated or corrupt (a failed checksum of
        :func:`write_dataset`), or lacks ``variables`` or ``attributes``.
    """
    import xarray as xr

    path = Path(path)
    if not path.exists():
        raise InputFileNotFoundError(f"{path}: no such {kind} file")
    if not path.is_file():
        raise InputError(f"{path}: a directory, not a {kind} file")
    again = "delete it and rerun snakemake (or the lsbg command that wrote it)"
    try:
        with xr.open_dataset(path, engine="netcdf4") as ds:
            ds = ds.load()
    except PermissionError:
        raise InputError(f"{path}: {kind} file not readable (permission denied)") from None
    # netCDF4 reports a truncated or corrupt file as OSError or RuntimeError
    # ("NetCDF: HDF error", also a failed checksum) or AttributeError (an
    # unreadable attribute); the try holds nothing but the reading.
    except (OSError, ValueError, RuntimeError, AttributeError) as err:
        # the reason without the path again (an OSError's strerror), in one line
        detail = getattr(err, "strerror", None) or (str(err).splitlines() or [repr(err)])[0]
        raise InputError(f"{path}: not a readable NetCDF file, truncated or corrupt "
                         f"({detail}); {again}") from None
    missing = [name for name in variables if name not in ds.variables]
    missing += [name for name in attributes if name not in ds.attrs]
    if missing:
        more = f" and {len(missing) - 5} more" if len(missing) > 5 else ""
        raise InputError(f"{path}: not {what} (missing {missing[:5]}{more}); {again}")
    ds.encoding["source"] = str(path)
    return ds


# ------------------------------------------------------------------- names
def number_label(value):
    """A number as it appears in file names: 35 -> "35", 37.5 -> "37.5" (no exponent).

    Parameters
    ----------
    value : float
        A spiral angle [deg], a torque [N m], a speed [deg/s], a factor [-].

    Returns
    -------
    str
    """
    return f"{float(value):.6f}".rstrip("0").rstrip(".")


def label_clashes(values, where, label=number_label):
    """Values of a list whose file-name labels equal an earlier one's, one line each.

    Parameters
    ----------
    values : list
        The list as the user wrote it (a sweep's angles, a sensitivity key's factors).
    where : str
        Its key path (``sweep.spiral_angles_deg``).
    label : callable, optional
        The value's part of a file name (default :func:`number_label`).

    Returns
    -------
    list of str
        ``where[k] = value: gives the same file name ... as where[j] = ...``.
    """
    seen, problems = {}, []
    for k, value in enumerate(values):
        name = label(value)
        if name in seen:
            first = seen[name]
            problems.append(f"{where}[{k}] = {value!r}: gives the same file name ({name}) as "
                            f"{where}[{first}] = {values[first]!r} (file names keep "
                            f"6 decimals)")
        else:
            seen[name] = k
    return problems


def fill_template(template, option, **fields):
    """A file name from a template with ``{name}`` fields (``lsbg points``, ``sensitivity``).

    Parameters
    ----------
    template : str
        E.g. ``results/runs/logarithmic_beta{spiral}_line_compiled.nc``.
    option : str
        The option that gave it, for the error message.
    **fields : str
        Values of the fields.

    Returns
    -------
    str

    Raises
    ------
    ValueError
        Naming the option if the template names an unknown field.
    """
    try:
        return template.format(**fields)
    except (KeyError, IndexError, ValueError) as error:
        raise ValueError(f"{option} {template!r}: bad template ({error!r}); fields: "
                         f"{', '.join('{' + name + '}' for name in fields)}") from None


class DuplicateKeyError(ValueError):
    """A YAML mapping names a key twice: YAML keeps the last silently, lsbg refuses."""


def load_yaml(stream, name="<yaml>"):
    """Read YAML (as ``yaml.safe_load``) refusing a key given twice in one mapping.

    Parameters
    ----------
    stream : str or file
    name : str
        The file's name, for the message.

    Raises
    ------
    DuplicateKeyError
        ``"{name}: line M: key 'contact.slices' again (first at line N): YAML
        would keep only the last"``: the key's path through the mappings.
    yaml.YAMLError
        Not valid YAML.
    """
    import yaml

    text = stream if isinstance(stream, str) else stream.read()
    node = yaml.compose(text, Loader=yaml.SafeLoader)
    if node is None:
        return None
    _refuse_duplicate_keys(node, name, [])
    loader = yaml.SafeLoader(text)
    try:
        return loader.construct_document(node)
    finally:
        loader.dispose()


def _refuse_duplicate_keys(node, name, path):
    import yaml

    if isinstance(node, yaml.MappingNode):
        seen = {}
        for key, value in node.value:
            label = str(key.value) if isinstance(key, yaml.ScalarNode) else str(key.start_mark)
            line = key.start_mark.line + 1
            if label in seen:
                raise DuplicateKeyError(
                    f"{name}: line {line}: key {'.'.join([*path, label])!r} again (first at line "
                    f"{seen[label]}): YAML would keep only the last")
            seen[label] = line
            _refuse_duplicate_keys(value, name, [*path, label])
    elif isinstance(node, yaml.SequenceNode):
        for k, item in enumerate(node.value):
            _refuse_duplicate_keys(item, name, [*path, f"[{k}]"])


def duplicate_key_problems(paths):
    """Keys given twice in one mapping of a configuration file, one line each.

    Snakemake (like YAML) keeps the last of two equal keys without a word, so a
    file that sets ``contact.slices`` twice runs with whichever came last;
    lsbg refuses it, naming the file, both lines and the key's path.

    Parameters
    ----------
    paths : iterable of str or os.PathLike
        The configuration files Snakemake read (``workflow.configfiles``).

    Returns
    -------
    list of str
    """
    import os

    import yaml

    problems = []
    for path in paths:
        relative = os.path.relpath(path)
        name = str(path) if relative.startswith("..") else relative
        try:
            with open(path, encoding="utf-8") as handle:
                load_yaml(handle, name)
        except DuplicateKeyError as error:
            problems.append(str(error))
        except (OSError, yaml.YAMLError):  # Snakemake has read it, or says why not itself
            continue
    return problems


def read_yaml_file(path, option="--config"):
    """A YAML file that holds a mapping (``{}`` if empty), read refusing duplicate keys.

    Parameters
    ----------
    path : str or os.PathLike
    option : str
        What gave the file (``"--config"``), for the message.

    Returns
    -------
    dict

    Raises
    ------
    InputError
        One line naming ``option`` and the file: it cannot be read, is not
        valid YAML (line and column), names a key twice, or holds no mapping.
    """
    import yaml

    try:
        with open(path, encoding="utf-8") as handle:
            data = load_yaml(handle, str(path))
    except DuplicateKeyError as error:
        raise InputError(f"{option} {error}") from None
    except OSError as error:
        raise InputError(f"{option} {path}: {error.strerror}") from None
    except yaml.YAMLError as error:
        # one line: where and what, without the YAML library's excerpt of the file
        mark = getattr(error, "problem_mark", None)
        where = f"line {mark.line + 1}, column {mark.column + 1}: " if mark else ""
        problem = getattr(error, "problem", None) or str(error).splitlines()[0]
        raise InputError(f"{option} {path}: not valid YAML ({where}{problem})") from None
    if data is None:
        return {}
    if not isinstance(data, dict):
        raise InputError(f"{option} {path}: must hold a mapping of keys")
    return data
