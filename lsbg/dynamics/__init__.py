"""Meshing dynamics of the gear pair: settings, the model, and three engines.

* :mod:`lsbg.dynamics.settings`: :class:`SimulationSettings` and the pinion's
  prescribed motion;
* :mod:`lsbg.dynamics.model`: :class:`MeshingModel` (geometry, contact,
  inertias), run records, :func:`load_model` and :func:`simulate`;
* :mod:`lsbg.dynamics.driveline`: the torsional driveline around the mesh
  (``simulation.boundary: driveline``), its modes and its equations;
* the engines, three independent integrators of the same model:
  :mod:`~lsbg.dynamics.pybullet_engine` (the multibody model in PyBullet,
  fixed step), :mod:`~lsbg.dynamics.scipy_engine` (scipy's LSODA) and
  :mod:`~lsbg.dynamics.compiled_engine` (an embedded Runge-Kutta loop compiled
  with numba).

Angles are forward rotations [rad] (``GearPair.rotation_axis``), speeds [rad/s].
"""

from lsbg import lazy_exports

#: Submodule -> the names it exports (imported when first used: reading a run's dataset,
#: lsbg.dynamics.dataset, needs neither the engines nor numba).
_EXPORTS = {
    "driveline": ("BOUNDARIES", "DRIVELINE_CONFIG_KEYS", "Driveline", "driveline_values"),
    "model": ("MeshingModel", "RunRecord", "Series", "load_model", "simulate"),
    "settings": ("COMPILED_METHODS", "ENGINES", "SCIPY_METHODS", "SIMULATION_CONFIG_KEYS",
                 "SimulationError", "SimulationSettings", "pinion_motion", "pinion_state"),
}
__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)

__all__ = [name for names in _EXPORTS.values() for name in names]
