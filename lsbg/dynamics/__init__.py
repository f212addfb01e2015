"""Meshing dynamics of the gear pair: settings, the model, and three engines.

* :mod:`lsbg.dynamics.settings`: :class:`SimulationSettings` and the pinion's
  prescribed motion;
* :mod:`lsbg.dynamics.model`: :class:`MeshingModel` (geometry, contact,
  inertias), run records, :func:`load_model` and :func:`simulate`;
* the engines, three independent integrators of the same model:
  :mod:`~lsbg.dynamics.pybullet_engine` (the multibody model in PyBullet,
  fixed step), :mod:`~lsbg.dynamics.scipy_engine` (scipy's LSODA) and
  :mod:`~lsbg.dynamics.compiled_engine` (an embedded Runge-Kutta loop compiled
  with numba).

Angles are forward rotations [rad] (``GearPair.rotation_axis``), speeds [rad/s].
"""

from lsbg.dynamics.model import MeshingModel, RunRecord, Series, load_model, simulate
from lsbg.dynamics.settings import (
    COMPILED_METHODS,
    ENGINES,
    SCIPY_METHODS,
    SIMULATION_CONFIG_KEYS,
    SimulationError,
    SimulationSettings,
    pinion_motion,
    pinion_state,
)

__all__ = ["MeshingModel", "RunRecord", "Series", "load_model", "simulate", "COMPILED_METHODS",
           "ENGINES", "SCIPY_METHODS", "SIMULATION_CONFIG_KEYS", "SimulationError",
           "SimulationSettings", "pinion_motion", "pinion_state"]
