"""The files of a design point's geometry directory: names, manifest, reading them back.

``lsbg geometry`` (:mod:`lsbg.solid.export`) writes a directory per design point;
the later stages (dynamics, loaded TCA, reports) read it back through this
module, which needs neither the meshes nor the solids' code.

A geometry directory proves what it is: its last file, ``manifest.json``
(:func:`write_manifest`), holds the size and SHA-256 of every other file and
the design point they belong to. Every reader (:func:`read_record`,
:func:`read_design`, :func:`geometry_directory`) checks it first and raises
:class:`InputError`, naming the file that is missing or changed and how to
regenerate it. Hashing all files of a directory costs about 5 ms (4.6 MB, the
STL meshes are most of it), so every read checks every file.
"""

from __future__ import annotations

import hashlib
import json
import re
from pathlib import Path

from lsbg.gear.design import CONFIG_KEYS, TRACES, DesignError, GearPairDesign
from lsbg.files import InputError, InputFileNotFoundError, file_digest, number_label

__all__ = ["FILE_NAMES", "OPTIONAL_FILE_NAMES", "MANIFEST", "read_record", "read_design",
           "geometry_directory", "write_manifest", "design_digest"]


#: File names inside a geometry directory (all listed in its manifest).
FILE_NAMES = {
    "design": "design.json", "flanks": "flanks.nc",
    "pinion_stl": "pinion.stl", "gear_stl": "gear.stl",
    "urdf": "pair.urdf", "picture": "pair.png",
}
#: Files a geometry directory may hold besides :data:`FILE_NAMES` (``lsbg geometry``
#: writes them unless told not to; ``lsbg points`` only when asked): the exact solids
#: as STEP (:mod:`lsbg.solid.step`). The manifest lists them when they are there.
OPTIONAL_FILE_NAMES = {"pinion_step": "pinion.step", "gear_step": "gear.step"}
#: The manifest of a geometry directory, written last (:func:`write_manifest`).
MANIFEST = "manifest.json"
#: Value of the manifest's ``format`` key.
MANIFEST_FORMAT = "lsbg geometry manifest 1"
#: Keys of ``design.json`` that the readers need: the design and the inertias.
REQUIRED_KEYS = (*CONFIG_KEYS, "axial_inertia_pinion_kg_m2", "axial_inertia_gear_kg_m2")
#: The workflow's name of a geometry directory (``lsbg.study.points.FILES["geometry"]``,
#: ``{trace}_beta{spiral}``); a directory so named must hold that design point.
POINT_NAME = re.compile(rf"^(?P<trace>{'|'.join(TRACES)})_beta(?P<spiral>[-+0-9.]+)$")


def _regenerate(directory):
    return (f"to regenerate it, delete {directory} and rerun snakemake (or rerun "
            f"'lsbg geometry --out {directory}' with its design options)")


def design_digest(record) -> str:
    """SHA-256 of a design's inputs: identifies a design point.

    Parameters
    ----------
    record : dict
        ``design.json`` record or :meth:`GearPairDesign.to_config` (paper units);
        only the keys of :data:`lsbg.gear.design.CONFIG_KEYS` count.

    Returns
    -------
    str
        64 hex digits of the canonical JSON (sorted keys, no spaces). A value
        survives the JSON round trip exactly, so the record read back from
        ``design.json`` gives the digest written.
    """
    config = {key: record[key] for key in CONFIG_KEYS if key in record}
    text = json.dumps(config, sort_keys=True, separators=(",", ":"), allow_nan=True)
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def _design_point(record):
    return {"trace": record["trace"], "spiral_angle_deg": record["spiral_angle_deg"]}


def _json_file(path, directory):
    """The content of a JSON file of a geometry directory; InputError if it is not JSON."""
    try:
        with open(path, encoding="utf-8") as handle:
            return json.load(handle)
    except (UnicodeDecodeError, json.JSONDecodeError) as error:
        where = f" (line {error.lineno})" if isinstance(error, json.JSONDecodeError) else ""
        raise InputError(f"{path}: not valid JSON{where}; {_regenerate(directory)}") from None


def write_manifest(directory) -> Path:
    """Write ``manifest.json`` of a geometry directory whose other files are complete.

    Parameters
    ----------
    directory : str or os.PathLike
        Holds every file of :data:`FILE_NAMES`.

    Returns
    -------
    pathlib.Path
        The manifest: ``format``, ``design_point`` (``trace``,
        ``spiral_angle_deg`` [deg]), ``design_sha256`` (:func:`design_digest`)
        and ``files``: name -> ``bytes`` [B] and ``sha256``. No time stamp:
        the same files give the same manifest, byte for byte.
    """
    directory = Path(directory)
    record = _json_file(directory / FILE_NAMES["design"], directory)
    manifest = {
        "format": MANIFEST_FORMAT,
        "design_point": _design_point(record),
        "design_sha256": design_digest(record),
        "files": {name: {"bytes": (directory / name).stat().st_size,
                         "sha256": file_digest(directory / name)}
                  for name in sorted(FILE_NAMES.values())
                  + sorted(n for n in OPTIONAL_FILE_NAMES.values() if (directory / n).is_file())},
    }
    path = directory / MANIFEST
    with open(path, "w", encoding="utf-8") as handle:
        json.dump(manifest, handle, indent=1, sort_keys=True)
        handle.write("\n")
    return path


# ----------------------------------------------------------------- reading
def _checked(geometry_dir):
    """(directory, design.json record) of a geometry directory that matches its manifest."""
    directory = Path(geometry_dir)
    if not directory.exists():
        raise InputFileNotFoundError(f"{directory}: no such geometry directory (written by "
                                     f"'lsbg geometry')")
    if not directory.is_dir():
        raise InputError(f"{directory}: a file, not a geometry directory (written by "
                         f"'lsbg geometry')")
    manifest_path = directory / MANIFEST
    if not manifest_path.is_file():
        if not any(directory.iterdir()):
            raise InputError(f"{directory}: an empty directory, not a geometry directory "
                             f"(written by 'lsbg geometry')")
        raise InputError(f"{directory}: no {MANIFEST}, not a complete geometry directory "
                         f"(interrupted, or written by an older lsbg); {_regenerate(directory)}")
    manifest = _json_file(manifest_path, directory)
    if not isinstance(manifest, dict):
        manifest = {}
    files = manifest.get("files")
    if manifest.get("format") != MANIFEST_FORMAT or not isinstance(files, dict) \
            or not set(FILE_NAMES.values()) <= set(files) \
            or not set(files) <= {*FILE_NAMES.values(), *OPTIONAL_FILE_NAMES.values()} \
            or not all(isinstance(entry, dict) for entry in files.values()):
        raise InputError(f"{manifest_path}: not a manifest of 'lsbg geometry' (format "
                         f"{MANIFEST_FORMAT!r}, every file of {sorted(FILE_NAMES.values())}); "
                         f"{_regenerate(directory)}")
    for name, entry in files.items():
        path = directory / name
        if not path.is_file():
            raise InputError(f"{path}: missing (listed in {MANIFEST}); {_regenerate(directory)}")
        # the size first: a truncated or grown file needs no hashing to be caught
        if path.stat().st_size != entry.get("bytes") or file_digest(path) != entry.get("sha256"):
            raise InputError(f"{path}: changed since 'lsbg geometry' wrote it (size or SHA-256 "
                             f"differs from {MANIFEST}); {_regenerate(directory)}")
    design_path = directory / FILE_NAMES["design"]
    record = _json_file(design_path, directory)
    missing = [key for key in REQUIRED_KEYS if key not in record] if isinstance(record, dict) \
        else list(REQUIRED_KEYS)
    if missing:
        raise InputError(f"{design_path}: not a design record of 'lsbg geometry' (missing "
                         f"{missing}); {_regenerate(directory)}")
    # The hashes above match, so these disagree only if the manifest was edited too.
    if manifest.get("design_point") != _design_point(record) \
            or manifest.get("design_sha256") != design_digest(record):
        raise InputError(f"{design_path}: not the design point of {MANIFEST} "
                         f"({manifest.get('design_point')}); {_regenerate(directory)}")
    named = POINT_NAME.match(directory.name)
    if named and (named["trace"] != record["trace"]
                  or named["spiral"] != number_label(record["spiral_angle_deg"])):
        raise InputError(f"{directory}: holds the {record['trace']} design point at spiral "
                         f"angle {number_label(record['spiral_angle_deg'])} deg, not the one "
                         f"its name says; {_regenerate(directory)}")
    return directory, record


def geometry_directory(geometry_dir) -> Path:
    """A geometry directory written by ``lsbg geometry``, checked against its manifest.

    Parameters
    ----------
    geometry_dir : str or os.PathLike

    Returns
    -------
    pathlib.Path
        ``geometry_dir``.

    Raises
    ------
    InputError
        In one line, naming the path: the directory does not exist
        (:class:`InputFileNotFoundError`), is a file, is empty or has no
        manifest; a file is missing or changed (size or SHA-256);
        ``design.json`` is not JSON, lacks keys of :data:`REQUIRED_KEYS` or
        holds another design point than the manifest; or the directory's name
        follows the workflow's ``{trace}_beta{spiral}`` (:data:`POINT_NAME`)
        but the design point is another.
    """
    return _checked(geometry_dir)[0]


def read_record(geometry_dir) -> dict:
    """The ``design.json`` record of a geometry directory, checked (:func:`geometry_directory`).

    Parameters
    ----------
    geometry_dir : str or os.PathLike

    Returns
    -------
    dict
        Keys carry their unit (see :func:`lsbg.solid.export.design_record`).

    Raises
    ------
    InputError
        See :func:`geometry_directory`.
    """
    return _checked(geometry_dir)[1]


def read_design(geometry_dir) -> GearPairDesign:
    """The design written into a geometry directory by ``lsbg geometry``.

    Parameters
    ----------
    geometry_dir : str or os.PathLike
        Directory holding ``design.json`` and the manifest.

    Returns
    -------
    GearPairDesign
        Equal to the design that was written.

    Raises
    ------
    InputError
        See :func:`geometry_directory`; also an invalid design value.
    """
    directory, record = _checked(geometry_dir)
    try:
        return GearPairDesign.from_config({key: record[key] for key in CONFIG_KEYS})
    except DesignError as error:
        raise InputError(f"{directory / FILE_NAMES['design']}: {error}; "
                         f"{_regenerate(directory)}") from None
