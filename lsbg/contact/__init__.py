"""Contact of the gear pair: the laws, the compiled kernels and the mesh's kernel data.

* :mod:`lsbg.contact.law`: the paper's IMPACT law (Eq. 8–11), friction and the
  line model's slice law, with their parameters (:class:`ContactParameters`);
* :mod:`lsbg.contact.kernels`: the compiled kernels of the point and the line
  model (numba, cached on disk);
* :mod:`lsbg.contact.mesh`: :class:`MeshContact`, the kernels' data built from
  the exact geometry, and the line model's stiffness calibration.
"""

from lsbg.contact.law import (
    CONTACT_CONFIG_KEYS,
    CONTACT_MODELS,
    ContactParameters,
    friction_coefficient,
    friction_coefficient_scalar,
    hertz_approach,
    hertz_stiffness,
    impact_force,
    impact_force_scalar,
    implied_correction_coefficient,
    line_load,
    line_load_scalar,
    step,
    step_scalar,
)
from lsbg.contact.mesh import (
    ISO_MESH_STIFFNESS,
    PHASE_SAMPLES_PER_PITCH,
    MeshContact,
    MeshForces,
    PairContact,
    calibrated_line_stiffness,
)

__all__ = [
    "CONTACT_CONFIG_KEYS", "CONTACT_MODELS", "ContactParameters", "friction_coefficient",
    "friction_coefficient_scalar", "hertz_approach", "hertz_stiffness", "impact_force",
    "impact_force_scalar", "implied_correction_coefficient", "line_load", "line_load_scalar",
    "step", "step_scalar", "ISO_MESH_STIFFNESS", "PHASE_SAMPLES_PER_PITCH", "MeshContact",
    "MeshForces", "PairContact", "calibrated_line_stiffness",
]
