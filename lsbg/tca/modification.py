"""Flank modification (ease-off) of the pinion's flanks.

Real spiral bevel gears are not conjugate: the pinion's flank is relieved
(crowned) so that the bearing contact is localized inside the flank and the
unloaded transmission error is a shallow parabola per mesh cycle (Litvin's
predesigned parabolic function; docs/model.md, "Flank modification").
:class:`FlankModification` describes the relief as a normal deviation of the
pinion's flank, removed from the tooth, in the ease-off coordinates every
bevel-gear tool plots it in:

* the **lengthwise** coordinate u = (R - R_m) / (b / 2): -1 at the toe,
  +1 at the heel (R the cone distance, R_m the mean cone distance, b the face
  width);
* the **profile** coordinate v = (psi - psi_c) / (Delta psi / 2): -1 and +1
  at the two ends of the active profile, where psi is the polar angle in the
  plane of action at which the flank point meets it (a function of the
  point's polar angle about the pinion axis only), psi_c the middle and
  Delta psi the width of the field of contact. On the drive side of the
  paper's pair v = +1 is the pinion's root end of the active profile and
  v = -1 its tip end; :func:`profile_coordinate` gives the sense for any pair.

The relief is

    delta(u, v) = C_L u^2 + C_P v^2 + B u v + C_beta u + C_alpha v + topography(u, v)
                  + C_a1 <1 - w_1 / L_1>  + C_a2 <1 - w_2 / L_2>,

with C_L the lengthwise crowning and C_P the profile crowning (reliefs at the
toe and heel on the middle of the profile, and at the ends of the active
profile in the middle of the face), B the bias (a twist: +B at the (u, v) =
(+1, +1) and (-1, -1) corners, -B at the other two), the first-order
corrections of the spiral angle C_beta u and of the pressure angle C_alpha v
(the flank turned about the mean point lengthwise and across the profile:
C_beta relieves the heel and adds at the toe), an optional measured
or designed topography on a (u, v) grid, and the linear tip reliefs of both
members: C_a1 at the pinion's tip end of the active profile, running out
over the fraction L_1 of the active profile (w_1 = (1 - s v) / 2 its
distance from that end, s = -1 or +1 the end the pinion's tip is at,
:func:`pinion_tip_end`; <x> = max(x, 0)), and the gear's C_a2 over L_2 from
the other end (w_2 = 1 - w_1), where the gear's tip meets the pinion. The
ease-off is relative: a relief of the gear's tip is carried by the pinion's
flank points it meets, which gives the same gap at every mesh position. The same definition applies to both
gear types, so their comparison is fair. All amounts are in metres inside and
in micrometres in the configuration (``flank_modification:``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from lsbg.memo import arrays_key, copied, memoised

__all__ = ["FlankModification", "TopographyError", "MODIFICATION_CONFIG_KEYS",
           "read_topography", "profile_coordinate", "pinion_tip_end", "lengthwise_coordinate", "pinion_relief",
           "relieved_flank", "flank_attributes"]

_UM = 1e-6

#: Configuration keys of ``flank_modification:`` and the field each sets.
MODIFICATION_CONFIG_KEYS = {
    "lengthwise_crowning_um": "lengthwise_crowning",
    "profile_crowning_um": "profile_crowning",
    "bias_um": "bias",
    "topography_file": "topography_file",
    "spiral_angle_correction_um": "spiral_angle_correction",
    "pressure_angle_correction_um": "pressure_angle_correction",
    "pinion_tip_relief_um": "pinion_tip_relief",
    "pinion_tip_relief_length": "pinion_tip_relief_length",
    "gear_tip_relief_um": "gear_tip_relief",
    "gear_tip_relief_length": "gear_tip_relief_length",
}

#: Keys of :data:`MODIFICATION_CONFIG_KEYS` that are fractions of the active profile,
#: not micrometres.
_FRACTION_KEYS = ("pinion_tip_relief_length", "gear_tip_relief_length")


class TopographyError(ValueError):
    """A topography file that is missing, of the wrong shape or with NaN."""


@dataclass(frozen=True)
class FlankModification:
    """Relief of the pinion's drive flank, normal to it, in SI units.

    Parameters
    ----------
    lengthwise_crowning : float
        C_L, relief at the toe and heel (u = -1, +1) on the middle of the
        profile [m], >= 0.
    profile_crowning : float
        C_P, relief at the ends of the active profile (v = -1, +1) in the
        middle of the face [m], >= 0.
    bias : float
        B, the twist term B u v [m].
    topography_file : str or None
        A CSV (columns ``u``, ``v``, ``relief_um`` on a full rectangular grid)
        or NetCDF file (variable ``relief`` [um] on dimensions ``u`` and
        ``v``) whose relief is added, interpolated bilinearly; the grid must
        cover -1 <= u, v <= 1.
    topography : tuple or None
        The file's grid once read: (u [-], v [-], relief [m]); set by
        :meth:`load`.
    spiral_angle_correction, pressure_angle_correction : float
        C_beta, C_alpha: the relief of the linear terms at the heel (u = +1)
        and at v = +1 [m], either sign.
    pinion_tip_relief, gear_tip_relief : float
        C_a1, C_a2: the linear tip relief of each member at its tip's end of
        the active profile [m], >= 0.
    pinion_tip_relief_length, gear_tip_relief_length : float
        L_1, L_2: the fraction of the active profile (in roll, from the tip's
        end) over which each relief runs out to zero [-], 0 < L <= 1.
    """

    lengthwise_crowning: float = 0.0
    profile_crowning: float = 0.0
    bias: float = 0.0
    topography_file: str | None = None
    topography: tuple | None = field(default=None, compare=False, repr=False)
    spiral_angle_correction: float = 0.0
    pressure_angle_correction: float = 0.0
    pinion_tip_relief: float = 0.0
    pinion_tip_relief_length: float = 0.25
    gear_tip_relief: float = 0.0
    gear_tip_relief_length: float = 0.25

    def __post_init__(self):
        for name in ("lengthwise_crowning", "profile_crowning", "pinion_tip_relief",
                     "gear_tip_relief"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, (int, float)) \
                    or not math.isfinite(value) or value < 0:
                raise ValueError(f"flank_modification.{name}_um = {_um(value)}: must be a "
                                 f"number >= 0 [um]")
        for name in ("bias", "spiral_angle_correction", "pressure_angle_correction"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, (int, float)) \
                    or not math.isfinite(value):
                raise ValueError(f"flank_modification.{name}_um = {_um(value)}: must be a "
                                 f"finite number [um]")
        for name in _FRACTION_KEYS:
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, (int, float)) \
                    or not (0.0 < value <= 1.0):
                raise ValueError(f"flank_modification.{name} = {value!r}: must be a fraction "
                                 f"of the active profile, 0 < L <= 1")

    # ------------------------------------------------------------- config
    @classmethod
    def from_config(cls, config, base=None):
        """Build from the ``flank_modification:`` section (micrometres).

        Parameters
        ----------
        config : dict or None
            Keys of :data:`MODIFICATION_CONFIG_KEYS`; missing keys are 0
            (no topography). None or {}: no modification.
        base : str or pathlib.Path, optional
            Directory a relative ``topography_file`` is read from (default:
            the working directory).

        Returns
        -------
        FlankModification
            With its topography read (:meth:`load`).

        Raises
        ------
        ValueError
            Naming the key and value (``flank_modification.<key>``).
        """
        kwargs = {}
        for key, value in (config or {}).items():
            if key not in MODIFICATION_CONFIG_KEYS:
                raise ValueError(f"flank_modification.{key} = {value!r}: unknown key "
                                 f"(known: {sorted(MODIFICATION_CONFIG_KEYS)})")
            name = MODIFICATION_CONFIG_KEYS[key]
            if name == "topography_file":
                if value is not None and not isinstance(value, str):
                    raise ValueError(f"flank_modification.{key} = {value!r}: must be a "
                                     f"file name or null")
                if value is not None and base is not None and not Path(value).is_absolute():
                    value = str(Path(base) / value)
                kwargs[name] = value
                continue
            if isinstance(value, bool) or not isinstance(value, (int, float)):
                raise ValueError(f"flank_modification.{key} = {value!r}: must be a number"
                                 + ("" if key in _FRACTION_KEYS else " [um]"))
            kwargs[name] = float(value) * (1.0 if key in _FRACTION_KEYS else _UM)
        return cls(**kwargs).load()

    def to_config(self):
        """The ``flank_modification:`` keys in micrometres (inverse of :meth:`from_config`)."""
        out = {"lengthwise_crowning_um": self.lengthwise_crowning / _UM,
               "profile_crowning_um": self.profile_crowning / _UM,
               "bias_um": self.bias / _UM,
               "topography_file": self.topography_file}
        if self.has_linear_terms:  # the keys of a study without them stay as they were
            out.update({"spiral_angle_correction_um": self.spiral_angle_correction / _UM,
                        "pressure_angle_correction_um": self.pressure_angle_correction / _UM})
        if self.has_tip_relief:
            out.update({"pinion_tip_relief_um": self.pinion_tip_relief / _UM,
                        "pinion_tip_relief_length": self.pinion_tip_relief_length,
                        "gear_tip_relief_um": self.gear_tip_relief / _UM,
                        "gear_tip_relief_length": self.gear_tip_relief_length})
        return out

    def load(self):
        """This modification with its topography file read (itself if none)."""
        if self.topography_file is None or self.topography is not None:
            return self
        return replace(self, topography=read_topography(self.topography_file))

    @property
    def is_zero(self):
        """True when the flank is the conjugate one (no relief anywhere)."""
        return (self.lengthwise_crowning == 0.0 and self.profile_crowning == 0.0
                and self.bias == 0.0 and self.topography_file is None
                and not self.has_tip_relief and not self.has_linear_terms)

    @property
    def has_linear_terms(self):
        """True when the spiral or pressure angle is corrected."""
        return self.spiral_angle_correction != 0.0 or self.pressure_angle_correction != 0.0

    @property
    def has_tip_relief(self):
        """True when either member's tip is relieved."""
        return self.pinion_tip_relief > 0.0 or self.gear_tip_relief > 0.0

    def relief_starts(self, pinion_tip=-1.0):
        """Profile coordinates v where the tip reliefs start (the kinks of the flank) [-].

        Parameters
        ----------
        pinion_tip : {-1, 1}
            The end of the active profile the pinion's tip is at (:func:`pinion_tip_end`).

        Returns
        -------
        dict
            ``{"pinion": v, "gear": v}`` for each member whose tip is relieved.
        """
        out = {}
        if self.pinion_tip_relief > 0.0:
            out["pinion"] = pinion_tip * (1.0 - 2.0 * self.pinion_tip_relief_length)
        if self.gear_tip_relief > 0.0:
            out["gear"] = -pinion_tip * (1.0 - 2.0 * self.gear_tip_relief_length)
        return out

    # ---------------------------------------------------------- evaluation
    def relief(self, u, v, pinion_tip=-1.0):
        """Relief delta(u, v) of the pinion flank, normal to it [m].

        Parameters
        ----------
        u : array_like
            Lengthwise coordinate, -1 at the toe, +1 at the heel [-].
        v : array_like
            Profile coordinate, -1 and +1 at the ends of the active profile [-].
        pinion_tip : {-1, 1}
            The end of the active profile the pinion's tip is at
            (:func:`pinion_tip_end`; -1 on the drive side of every lsbg pair
            so far), which places the tip reliefs.

        Returns
        -------
        numpy.ndarray
            Material removed from the conjugate flank [m] (negative: added).
        """
        u = np.asarray(u, dtype=float)
        v = np.asarray(v, dtype=float)
        out = self.lengthwise_crowning * u**2 + self.profile_crowning * v**2 + self.bias * u * v
        if self.has_linear_terms:
            out = out + self.spiral_angle_correction * u + self.pressure_angle_correction * v
        if self.has_tip_relief:
            from_pinion_tip = 0.5 * (1.0 - pinion_tip * v)
            out = out + self.pinion_tip_relief * np.maximum(
                1.0 - from_pinion_tip / self.pinion_tip_relief_length, 0.0)
            out = out + self.gear_tip_relief * np.maximum(
                1.0 - (1.0 - from_pinion_tip) / self.gear_tip_relief_length, 0.0)
        if self.topography_file is not None:
            grid_u, grid_v, relief = self.load().topography
            from scipy.interpolate import RegularGridInterpolator

            table = RegularGridInterpolator((grid_u, grid_v), relief, method="linear",
                                            bounds_error=False, fill_value=None)
            points = np.stack(np.broadcast_arrays(u, v), axis=-1)
            out = out + table(points)
        return out

    def largest_relief(self, n=41):
        """Largest |relief| over the flank, -1 <= u, v <= 1 [m] (grid of n x n)."""
        u, v = np.meshgrid(np.linspace(-1, 1, n), np.linspace(-1, 1, n), indexing="ij")
        return float(np.abs(self.relief(u, v)).max())


def _um(value):
    try:
        return f"{float(value) / _UM:g}"
    except (TypeError, ValueError):
        return repr(value)


# ------------------------------------------------------------------ coordinates
def lengthwise_coordinate(design, cone_distance):
    """u = (R - R_m) / (b / 2): -1 at the toe, +1 at the heel [-].

    Parameters
    ----------
    design : lsbg.gear.design.GearPairDesign
    cone_distance : array_like
        Distance R from the apex [m].
    """
    return (np.asarray(cone_distance, dtype=float) - design.mean_cone_distance) \
        / (0.5 * design.face_width)


def profile_coordinate(pair, polar_angle, side="drive"):
    """v of pinion flank points from their polar angle about the pinion axis [-].

    A pinion flank point at polar angle theta meets the plane of action at
    psi = psi_g + s chi(theta) (:meth:`lsbg.gear.geometry.GearPair.roll_angle`),
    at every cone distance; v maps the field of contact psi_lo..psi_hi to
    -1..+1.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    polar_angle : array_like
        Angle theta between the point and the pinion axis [rad].
    side : {"drive", "coast"}

    Returns
    -------
    numpy.ndarray
        v [-] (beyond +-1 outside the active profile).
    """
    plane = pair.planes[side]
    psi = plane.tangency_angle[1] + plane.roll_sign[1] * pair.roll_angle(1, polar_angle)
    return field_profile_coordinate(plane, psi)


def pinion_tip_end(pair, side="drive"):
    """The end of the active profile, v = -1 or +1, that the pinion's tip is at [-].

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    side : {"drive", "coast"}
    """
    tip = profile_coordinate(pair, pair.design.tip_angle(1), side)
    return -1.0 if float(tip) < 0 else 1.0


def field_profile_coordinate(plane, psi):
    """v of a polar angle psi in the plane of action (-1..+1 over the field) [-]."""
    psi_lo, psi_hi = plane.field[:2]
    return (np.asarray(psi, dtype=float) - 0.5 * (psi_lo + psi_hi)) / (0.5 * (psi_hi - psi_lo))


# ------------------------------------------------------------ the relieved flank
def pinion_relief(pair, modification, cone_distance, polar_angle):
    """The modification at pinion flank points given as (R, theta) [m].

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    modification : FlankModification
    cone_distance : array_like
        R [m].
    polar_angle : array_like
        theta, about the pinion axis [rad].
    """
    return modification.relief(lengthwise_coordinate(pair.design, cone_distance),
                               profile_coordinate(pair, polar_angle), pinion_tip_end(pair))


def relieved_flank(pair, modification, cone_distance, psi, side="drive", polar_range=None):
    """Points and outward normals of the pinion's flank of tooth 0 at (R, psi).

    The flank point at cone distance R that meets the plane of action at the
    polar angle psi (the roll inverted: cos(theta) = cos(delta_b1) cos(chi)),
    moved into the tooth by the modification on the drive side; the coast
    flank stays conjugate.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    modification : FlankModification
    cone_distance, psi : array_like
        R [m] and the polar angle in the plane of action [rad], broadcast.
    side : {"drive", "coast"}
    polar_range : (float, float), optional
        Bounds theta is clipped to [rad] (against rounding at the flank's ends).

    Returns
    -------
    points, normals : numpy.ndarray, shape (..., 3)
        In the pinion's body frame [m] and outward unit normals [-].
    relief : numpy.ndarray
        The material removed [m] (0 on the coast side).

    Notes
    -----
    The flank does not depend on the assembly's displacements, so the cells
    of a V-H map ask for the same grids again and again; the last
    :data:`FLANK_MEMO_SIZE` results per pair are kept (keyed by the
    modification, the side, the clip and the points' values and memory
    layout, :func:`lsbg.memo.arrays_key`; :func:`lsbg.memo.memoised`) and
    copies returned.
    """
    rho, psi = np.broadcast_arrays(np.asarray(cone_distance, float), np.asarray(psi, float))
    clip = None if polar_range is None else tuple(float(x) for x in polar_range)
    key = (modification, side, clip, arrays_key(rho, psi))
    return copied(memoised(pair, "relieved_flank", key,
                           lambda: _relieved_flank(pair, modification, rho, psi, side, clip),
                           FLANK_MEMO_SIZE))


#: Flank grids kept per pair by :func:`relieved_flank`.
FLANK_MEMO_SIZE = 8


def _relieved_flank(pair, modification, rho, psi, side, polar_range):
    plane = pair.planes[side]
    chi = np.maximum(plane.roll_sign[1] * (psi - plane.tangency_angle[1]), 0.0)
    theta = np.arccos(math.cos(pair.design.base_cone_angle(1)) * np.cos(chi))
    if polar_range is not None:
        theta = np.clip(theta, *polar_range)
    points, normals = pair.flank(1, side, rho, theta)
    relief = (modification.relief(lengthwise_coordinate(pair.design, rho),
                                  field_profile_coordinate(plane, psi), pinion_tip_end(pair))
              if side == "drive" else np.zeros(rho.shape))
    return points - relief[..., None] * normals, normals, relief


def flank_attributes(modification, misalignment):
    """Dataset attributes of the flanks: the ``flank_modification`` and
    ``misalignment`` keys (configuration units), prefixed with their section."""
    return {**{f"flank_modification_{k}": ("" if v is None else v)
               for k, v in modification.to_config().items()},
            **{f"misalignment_{k}": v for k, v in misalignment.to_config().items()}}


# ------------------------------------------------------------------ topography
def read_topography(path):
    """Read a designed or measured topography: (u, v, relief [m]).

    Parameters
    ----------
    path : str or pathlib.Path
        CSV with columns ``u``, ``v``, ``relief_um`` (one row per grid point
        of a full rectangular grid) or NetCDF (``.nc``) with variable
        ``relief`` [um] on dimensions ``u`` and ``v``.

    Returns
    -------
    tuple
        Increasing u [-], increasing v [-], relief [m] of shape (u, v).

    Raises
    ------
    TopographyError
        Naming the file: missing, unreadable, not a full grid, not covering
        -1..1 in u and v, or with NaN.
    """
    path = Path(path)
    where = f"flank_modification.topography_file = {str(path)!r}"
    if not path.is_file():
        raise TopographyError(f"{where}: no such file")
    try:
        if path.suffix == ".nc":
            import xarray as xr

            with xr.open_dataset(path) as ds:
                if "relief" not in ds or set(ds["relief"].dims) != {"u", "v"}:
                    raise TopographyError(f"{where}: needs a variable 'relief' [um] on "
                                          f"dimensions ('u', 'v')")
                relief = ds["relief"].transpose("u", "v")
                u, v, values = (np.asarray(relief["u"], float), np.asarray(relief["v"], float),
                                np.asarray(relief, float))
        else:
            import pandas as pd

            table = pd.read_csv(path)
            missing = {"u", "v", "relief_um"} - set(table.columns)
            if missing:
                raise TopographyError(f"{where}: columns {sorted(missing)} missing "
                                      f"(needs u, v, relief_um)")
            u = np.unique(table["u"].to_numpy(float))
            v = np.unique(table["v"].to_numpy(float))
            if len(table) != u.size * v.size or table.duplicated(["u", "v"]).any():
                raise TopographyError(f"{where}: {len(table)} rows are not a full grid of "
                                      f"{u.size} u x {v.size} v values")
            table = table.sort_values(["u", "v"])
            values = table["relief_um"].to_numpy(float).reshape(u.size, v.size)
    except TopographyError:
        raise
    except Exception as err:  # unreadable: name the file, keep the reason
        raise TopographyError(f"{where}: cannot be read ({err})") from err
    if u.size < 2 or v.size < 2:
        raise TopographyError(f"{where}: needs at least 2 values of u and of v "
                              f"(has {u.size} x {v.size})")
    if not (np.all(np.isfinite(values)) and np.all(np.isfinite(u)) and np.all(np.isfinite(v))):
        raise TopographyError(f"{where}: contains NaN or infinite values")
    order_u, order_v = np.argsort(u), np.argsort(v)
    u, v, values = u[order_u], v[order_v], values[np.ix_(order_u, order_v)]
    if u[0] > -1 or u[-1] < 1 or v[0] > -1 or v[-1] < 1:
        raise TopographyError(f"{where}: the grid covers u {u[0]:g}..{u[-1]:g}, "
                              f"v {v[0]:g}..{v[-1]:g}; it must cover -1..1 in both")
    return u, v, values * _UM

