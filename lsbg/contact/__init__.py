"""Contact of the gear pair: the laws, the compiled kernels and the mesh's kernel data.

* :mod:`lsbg.contact.parameters`: the parameters of both models
  (:class:`ContactParameters`), SI inside, the paper's units at the edges;
* :mod:`lsbg.contact.law`: the paper's IMPACT law (Eq. 8–11), friction and the
  line model's slice law;
* :mod:`lsbg.contact.hertz`: the Hertz stiffness behind the IMPACT law's k
  (Eq. 9);
* :mod:`lsbg.contact.kernels`: the compiled kernels of the point and the line
  model (numba, cached on disk);
* :mod:`lsbg.contact.statics`: the line model's mismatch at rest under a torque;
* :mod:`lsbg.contact.slices`: the line model's stiffness per slice from the
  tooth's own compliance (:class:`SliceStiffness`);
* :mod:`lsbg.contact.mesh`: :class:`MeshContact`, the kernels' data built from
  the exact geometry, and the line model's stiffness calibration;
* :mod:`lsbg.contact.bands`: where the line model's bands of a contact line lie
  in the field of contact (the FE and the optimiser's loaded TCAs).
"""

from lsbg import lazy_exports

#: Submodule -> the names it exports (imported when first used: the laws and
#: kernels load numba, which a stage that only needs the parameters does not).
_EXPORTS = {
    "hertz": ("hertz_approach", "hertz_stiffness", "implied_correction_coefficient"),
    "law": ("friction_coefficient", "friction_coefficient_scalar", "impact_force",
            "impact_force_scalar", "line_load", "line_load_scalar", "step", "step_scalar"),
    "parameters": ("CONTACT_CONFIG_KEYS", "CONTACT_MODELS", "ContactParameters"),
    "mesh": ("ISO_MESH_STIFFNESS", "PHASE_SAMPLES_PER_PITCH", "MeshContact", "MeshForces",
             "PairContact", "calibrated_line_stiffness"),
}
__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)

__all__ = [name for names in _EXPORTS.values() for name in names]
