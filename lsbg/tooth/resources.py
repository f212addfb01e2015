"""What the tooth's FE compliance costs, before it runs: DOFs, memory and time.

:func:`lsbg.tooth.compliance.tooth_compliance` meshes a segment of each member
with P2 tetrahedra and factorises its stiffness; a mesh too fine for the
machine (or for a job's time limit) should be rejected by the configuration
check before any job starts. :func:`fe_resource_estimate` predicts the
degrees of freedom from the element sizes the mesh will have
(:func:`lsbg.tooth.compliance.mesh_sizes`) and scales the peak memory and the
wall time from them with a model fitted to this code's runs
(:data:`RESOURCE_MODEL`). It only estimates; nothing here changes the
compliance.

SI units (bytes, seconds).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from lsbg.tooth.compliance import FEMeshSettings, mesh_sizes

__all__ = ["RESOURCE_MODEL", "FEResources", "fe_resource_estimate"]

#: The resource model of :func:`fe_resource_estimate`, fitted to this code's
#: meshes and runs with 7-tooth segments (3 designs, 2 members, 18 settings
#: meshed; 7 tooth sizes run, 0.25 to 0.52, on one core of a shared 2-core
#: x86-64 machine). DOFs of a member: ``dofs_tooth * V_t / h^3 + dofs_fillet
#: * (b / h_f + b / h_c) + dofs_body * V_s / H^3`` (V_t = b (h_a + h_f) pi m_mn
#: the loaded tooth's band, h its element size; b the face width, h_f and h_c
#: the drive and coast fillets' element sizes: the graded tubes along them;
#: V_s the segment's volume, H the body size): within 5 % of the meshes (rms
#: 3 %; 3-tooth segments come out about 10 % below it). Seconds of a member
#: (geometry, meshing, assembly, factorisation, solves): ``seconds_base +
#: seconds_scale (N / 1e4)^seconds_power``, within 23 % (the geometry's OCC
#: booleans are most of the base). Peak memory of the process:
#: ``memory_base + memory_scale (N_max / 1e4)^memory_power``, within 9 %.
RESOURCE_MODEL = {"dofs_tooth": 13.49, "dofs_fillet": 293.8, "dofs_body": 21.42,
                  "seconds_base": 2.393, "seconds_scale": 0.1005, "seconds_power": 1.941,
                  "memory_base": 1.5e8, "memory_scale": 1.018e8, "memory_power": 1.155}


@dataclass(frozen=True)
class FEResources:
    """Estimated cost of :func:`lsbg.tooth.compliance.tooth_compliance` (both members).

    Attributes
    ----------
    dofs : int
        Degrees of freedom of both segments together [-].
    dofs_pinion, dofs_gear : int
        Of each member's segment [-].
    memory : float
        Peak resident memory of the process [bytes] (the larger member's
        factorisation; the members run one after the other).
    seconds : float
        Wall time on one core [s], both members, Python's imports excluded
        (about 0.5 s more in a fresh process).
    """

    dofs: int
    dofs_pinion: int
    dofs_gear: int
    memory: float
    seconds: float


def fe_resource_estimate(pair, settings=None):
    """Degrees of freedom, peak memory and wall time of a compliance, before it runs.

    For a configuration check: a mesh too fine for the machine (or for a
    job's time limit) can be rejected before any job starts. The model
    (:data:`RESOURCE_MODEL`) counts the elements of the segment's mesh as
    the size field grades them (the loaded tooth, the fillets' tubes, the
    rim) and scales time and memory from the DOFs as measured; it takes a few
    milliseconds.

    Parameters
    ----------
    pair : lsbg.gear.geometry.GearPair
    settings : FEMeshSettings, optional
        Default: ``FEMeshSettings()``.

    Returns
    -------
    FEResources
        E.g. the paper's pair at 35 deg with the default settings: about
        85 000 DOFs and 0.7 GB.
    """
    from lsbg.solid.mass import quadrature_mass_properties

    settings = settings or FEMeshSettings()
    model = RESOURCE_MODEL
    d = pair.design
    normal_module = d.mean_module * math.cos(d.spiral_angle)
    dofs = []
    for member in (1, 2):
        sizes = mesh_sizes(pair, member, settings)
        band = d.face_width * (d.addendum + d.dedendum) * math.pi * normal_module
        segment = min(settings.segment_teeth / d.teeth[member - 1], 1.0) \
            * quadrature_mass_properties(pair, member).volume
        dofs.append(model["dofs_tooth"] * band / sizes["tooth"] ** 3
                    + model["dofs_fillet"] * d.face_width * (1 / sizes["fillet"]
                                                             + 1 / sizes["coast_fillet"])
                    + model["dofs_body"] * segment / sizes["body"] ** 3)
    seconds = sum(model["seconds_base"] + model["seconds_scale"]
                  * (n / 1e4) ** model["seconds_power"] for n in dofs)
    memory = model["memory_base"] + model["memory_scale"] * (max(dofs) / 1e4) ** model[
        "memory_power"]
    return FEResources(dofs=int(round(sum(dofs))), dofs_pinion=int(round(dofs[0])),
                       dofs_gear=int(round(dofs[1])), memory=float(memory), seconds=float(seconds))
