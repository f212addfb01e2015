"""The files of a design point's geometry directory: names and reading them back.

``lsbg geometry`` (:mod:`lsbg.export`) writes a directory per design point;
the later stages (dynamics, loaded TCA, reports) read it back through this
module, which needs neither the meshes nor trimesh.
"""

from __future__ import annotations

import json
from pathlib import Path

from lsbg.design import CONFIG_KEYS, GearPairDesign

#: File names inside a geometry directory.
FILE_NAMES = {
    "design": "design.json", "flanks": "flanks.nc",
    "pinion_stl": "pinion.stl", "gear_stl": "gear.stl",
    "pinion_obj": "pinion.obj", "gear_obj": "gear.obj",
    "urdf": "pair.urdf", "picture": "pair.png",
}


def read_record(geometry_dir) -> dict:
    """The ``design.json`` record of a geometry directory (or the file itself).

    Parameters
    ----------
    geometry_dir : str or os.PathLike

    Returns
    -------
    dict
        Keys carry their unit (see :func:`lsbg.export.design_record`).

    Raises
    ------
    FileNotFoundError
        Naming the directory if it holds no ``design.json``.
    """
    path = Path(geometry_dir)
    if path.is_dir():
        path = path / FILE_NAMES["design"]
    if not path.is_file():
        raise FileNotFoundError(f"{geometry_dir}: no design.json (not a geometry directory "
                                f"of 'lsbg geometry')")
    with open(path, encoding="utf-8") as handle:
        return json.load(handle)


def read_design(geometry_dir) -> GearPairDesign:
    """The design written into a geometry directory by ``lsbg geometry``.

    Parameters
    ----------
    geometry_dir : str or os.PathLike
        Directory holding ``design.json`` (or the file itself).

    Returns
    -------
    GearPairDesign
        Equal to the design that was written.
    """
    record = read_record(geometry_dir)
    return GearPairDesign.from_config({key: record[key] for key in CONFIG_KEYS if key in record})
