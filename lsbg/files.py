"""The files of a design point's geometry directory: names and reading them back.

``lsbg geometry`` (:mod:`lsbg.export`) writes a directory per design point;
the later stages (dynamics, loaded TCA, reports) read it back through this
module, which needs neither the meshes nor the solids' code.
"""

from __future__ import annotations

import json
from pathlib import Path

from lsbg.design import CONFIG_KEYS, GearPairDesign

#: File names inside a geometry directory.
FILE_NAMES = {
    "design": "design.json", "flanks": "flanks.nc",
    "pinion_stl": "pinion.stl", "gear_stl": "gear.stl",
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
