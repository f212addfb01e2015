"""A design's load curve: the FE loaded TCA and ISO 10300 on the same torques."""

import numpy as np
import pytest

from lsbg.config import resolve_config
from lsbg.contact import ContactParameters, MeshContact
from lsbg.gear.design import GearPairDesign
from lsbg.gear.geometry import GearPair
from lsbg.practice.load_curve import load_curve, load_torques
from lsbg.rating.config import rate_design


@pytest.fixture(scope="module")
def curve(coarse_compliance):
    pair = GearPair(GearPairDesign())
    compliance = coarse_compliance   # the session's (tests/conftest.py)
    config = resolve_config([], [])
    return load_curve(MeshContact(pair, ContactParameters(model="line")), compliance, config,
                      [0.5, 1.0], others=[1964.99], phases=16)


def test_the_torques_are_the_rated_fractions_and_the_others():
    np.testing.assert_allclose(load_torques(400.0, [1.0, 0.25], [1964.99, 100.0]),
                               [100.0, 400.0, 1964.99])
    with pytest.raises(ValueError, match="rated_torque = -1"):
        load_torques(-1.0, [1.0])


def test_iso_stresses_sit_on_the_same_torques(curve):
    rated = curve.attrs["rated_torque_pitting_N_m"]
    torque = curve["torque"].values
    np.testing.assert_allclose(torque, np.round([0.5 * rated, rated, 1964.99], 3))
    # at the rated pitting torque sigma_H is the permissible stress (K_v = 1): S_H = 1
    config = resolve_config([], [])
    permissible, _, _ = rate_design(GearPairDesign(), config["rating"], config["tooth"], 100.0,
                                    np.radians(config["simulation"]["pinion_speed_deg_s"]),
                                    dynamic_factor=1.0)
    assert float(curve["iso_contact_stress"][1]) == pytest.approx(
        min(permissible.permissible_contact_stress) * 1e-6, rel=1e-5)   # (torques to 1 mN m)
    # sigma_H grows as the root of the torque, sigma_F with the torque
    h = curve["iso_contact_stress"].values
    assert h[2] / h[1] == pytest.approx(np.sqrt(torque[2] / torque[1]), rel=1e-9)
    f = curve["iso_root_stress_pinion"].values
    assert f[2] / f[0] == pytest.approx(torque[2] / torque[0], rel=1e-9)
    # the FE side: the cycle's largest pressure and root stress grow with the load
    assert np.all(np.diff(curve["max_contact_pressure"].max("mesh_phase").values) > 0)
    assert np.all(np.diff(curve["root_stress_pinion"].max("mesh_phase").values) > 0)
    assert curve.attrs["design_trace"] == "logarithmic"
    assert curve.attrs["design_set"] == "paper"
