"""The objectives and constraints respond to the ease-off as the physics says."""

import math

import numpy as np
import pytest

from lsbg.optimise.friction import Lubricant
from lsbg.optimise.loaded import loaded_points
from lsbg.optimise.objectives import (CONSTRAINTS, OBJECTIVES, QUANTITIES, EvaluationSettings,
                                      Evaluator)
from lsbg.tca.checks import normal_backlash
from lsbg.tca.misalignment import Misalignment
from lsbg.tca.modification import FlankModification
from lsbg.tooth.local import relative_curvature
from lsbg.tooth.reference import reduced_modulus

from tests.optimise.conftest import RATED, edge_radius


@pytest.fixture(scope="module")
def evaluators(pairs, envelope):
    return {trace: Evaluator(pair, EvaluationSettings(
        rated_torque=RATED, corners=envelope, edge_radius=edge_radius(pair.design)))
        for trace, pair in pairs.items()}


def crowned(lengthwise, profile=10.0, **tips):
    return FlankModification(lengthwise_crowning=lengthwise * 1e-6,
                             profile_crowning=profile * 1e-6,
                             **{k: v * 1e-6 for k, v in tips.items()})


def test_an_evaluation_gives_every_quantity(evaluators):
    out = evaluators["logarithmic"].evaluate(crowned(25, 5))
    assert set(out) == set(QUANTITIES) and set(OBJECTIVES) | set(CONSTRAINTS) <= set(out)
    assert all(math.isfinite(v) for v in out.values())
    assert out["mesh_loss"] == pytest.approx(100 - out["efficiency"])


def test_conjugate_pair_has_no_unloaded_transmission_error(evaluators):
    out = evaluators["circular"].evaluate(FlankModification())
    # zero to the quick grid's refinement (46 urad for the 25/5 um crowning)
    assert abs(out["unloaded_transmission_error"]) < 0.01  # urad
    # loaded, the mesh stiffness still varies: a TE of its own
    assert out["transmission_error"] > 1.0


@pytest.mark.parametrize("trace", ["logarithmic", "circular"])
def test_more_lengthwise_crowning_moves_the_pattern_less(evaluators, trace):
    moves = [evaluators[trace].evaluate(crowned(c))["pattern_movement"] for c in (20, 45)]
    assert moves[1] < 0.8 * moves[0]


def test_tip_relief_takes_load_off_the_edges(evaluators):
    bare, relieved = (evaluators["logarithmic"].evaluate(crowned(35, 5, **tips)) for tips in (
        {}, {"pinion_tip_relief": 25, "gear_tip_relief": 25}))
    assert relieved["aligned_edge_load_share"] < 0.3 * bare["aligned_edge_load_share"]
    # ... at the price of a larger transmission error at part load
    assert relieved["transmission_error"] > bare["transmission_error"]


def test_relief_within_the_backlash_by_hand(evaluators, pairs):
    out = evaluators["logarithmic"].evaluate(crowned(25, 5))
    # the largest relief is at the flank's corners: C_L + C_P = 30 um; j_n = j_t cos(20) cos(35)
    design = pairs["logarithmic"].design
    j_n = 0.1 * math.cos(math.radians(20)) * math.cos(math.radians(35)) * 1e3
    assert normal_backlash(design) * 1e6 == pytest.approx(j_n, rel=1e-9)
    assert out["relief_backlash"] == pytest.approx(30.0 - j_n, abs=1e-9)


def test_contact_pressure_is_hertz_on_the_exact_curvature(evaluators, pairs):
    evaluator, pair = evaluators["circular"], pairs["circular"]
    modification = crowned(30, 10, pinion_tip_relief=20, gear_tip_relief=20)
    out = evaluator.evaluate(modification)
    state = loaded_points(evaluator.contact(modification, Misalignment()), [RATED], 24)
    points, q = state.points, state.line_load[0]
    flank = points.inside & ~points.profile_edge(*evaluator.active) & (q > 0)
    for v in (-1.0 + 0.5, 1.0 - 0.5):   # the tip reliefs' starts (L = 0.25), kinks
        centre = 0.5 * sum(pair.planes["drive"].field[:2])
        half = 0.5 * np.diff(pair.planes["drive"].field[:2])[0]
        flank &= ~((points.psi_from < centre + v * half) & (centre + v * half < points.psi_to))
    e_star = reduced_modulus(206e9, 0.3, 206e9, 0.3)
    pressure = np.sqrt(q[flank] * e_star * relative_curvature(pair, points.rho[flank],
                                                              points.psi[flank]) / np.pi)
    assert out["contact_pressure"] == pytest.approx(pressure.max() * 1e-6, rel=1e-3)


def test_conjugate_pressure_grows_as_the_root_of_the_load(pairs):
    """Conjugate flanks touch along whole lines at every load: the line load is linear in the
    torque and Hertz's pressure p0 = sqrt(q E* / (pi R)) goes as its square root."""
    pressure = [Evaluator(pairs["logarithmic"], EvaluationSettings(
        rated_torque=torque, load_factors=(1.0,), phases=12)).evaluate(
        FlankModification())["contact_pressure"] for torque in (RATED, 4 * RATED)]
    assert pressure[1] / pressure[0] == pytest.approx(2.0, rel=1e-9)


def test_the_friction_law_changes_the_loss_not_the_loads(pairs):
    pair = pairs["logarithmic"]
    modification = crowned(30, 10)
    smooth = Lubricant(roughness=0.4e-6)
    out = {law: Evaluator(pair, EvaluationSettings(rated_torque=RATED, friction_law=law,
                                                   lubricant=smooth)).evaluate(modification)
           for law in ("iso_tr_14179_2", "benedict_kelley")}
    a, b = out.values()
    assert a["transmission_error"] == b["transmission_error"]
    assert a["mesh_loss"] != b["mesh_loss"]
    for figures in out.values():
        assert 98.0 < figures["efficiency"] < 99.7
        assert 0.02 < figures["friction_coefficient"] < 0.1
