"""Candidates at converged positions and under the FE loaded TCA (lsbg.optimise.verdict)."""

import dataclasses

import numpy as np
import pytest

from lsbg.optimise.verdict import (FE_QUANTITIES, STATE_FIGURES, converged, fe_combined,
                                   fe_state_figures)


def test_positions_double_until_every_value_changes_less_than_the_tolerance():
    asked = []

    def evaluate(n):
        asked.append(n)
        # a sampled peak's error falls as 1/n^2: 1 + 4/n^2
        return {"te": np.array([1.0 + 4.0 / n ** 2, 2.0 + 100.0 / n ** 2])}

    values, resolution = converged(evaluate, 8, 0.01, 1024)
    # the second design decides: 100/n^2 - 25/n^2 = 75/n^2 < 0.02 at n = 64
    assert resolution.positions == 64 and resolution.converged
    assert asked == [8, 16, 32, 64, 128]
    assert values["te"][1] == pytest.approx(2.0 + 100.0 / 64 ** 2)
    assert resolution.changes[-1] < 0.01 <= resolution.changes[-2]
    # where the largest resolution comes first, the run says so
    values, resolution = converged(evaluate, 8, 1e-6, 64)
    assert resolution.positions == 64 and not resolution.converged
    assert resolution.attributes("uniform")["uniform_converged"] == 0


def test_only_the_compared_quantities_decide():
    def evaluate(n):
        return {"te": np.array([1.0]), "share": np.array([1e-9 * (-1) ** int(np.log2(n))])}

    _, resolution = converged(evaluate, 8, 0.01, 64, compared=("te",))
    assert resolution.positions == 8 and resolution.converged
    _, resolution = converged(evaluate, 8, 0.01, 64)
    assert not resolution.converged  # a share about 0 never converges relatively
    with pytest.raises(ValueError, match="largest = 12"):
        converged(evaluate, 8, 0.01, 12)
    with pytest.raises(ValueError, match="tolerance = 0"):
        converged(evaluate, 8, 0, 64)


def test_the_combined_figures_take_the_worst_of_both_groups():
    aligned = {"transmission_error": 30.0, "rated_transmission_error": 28.0,
               "contact_pressure": 1900.0, "peak_contact_pressure": 2100.0,
               "root_stress_pinion": 500.0, "root_stress_gear": 520.0}
    corners = {"envelope_transmission_error": 45.0, "peak_contact_pressure": 2400.0,
               "root_stress_pinion": 610.0, "root_stress_gear": 480.0}
    out = fe_combined(aligned, corners)
    assert set(out) == set(FE_QUANTITIES)
    assert float(out["envelope_transmission_error"]) == 45.0
    assert float(out["peak_contact_pressure"]) == 2400.0
    assert float(out["root_stress"]) == 610.0 and float(out["root_stress_gear"]) == 520.0
    assert float(out["transmission_error"]) == 30.0


def test_the_aligned_figures_are_the_fe_loaded_tca_of_lsbg_ltca(coarse_compliance):
    """The choice's FE numbers are the verdict's: the same flanks (the search's separation
    cache against RealFlanks, as lsbg ltca builds them) and the same solver."""
    from lsbg.contact import ContactParameters, MeshContact
    from lsbg.gear.design import GearPairDesign
    from lsbg.gear.geometry import GearPair
    from lsbg.optimise.objectives import EvaluationSettings, Evaluator
    from lsbg.tca.modification import FlankModification
    from lsbg.tca.separation import RealFlanks
    from lsbg.tooth.ltca import fe_loaded_tca

    pair = GearPair(GearPairDesign())
    settings = EvaluationSettings(rated_torque=480.0, load_factors=(0.5, 1.0), phases=16)
    evaluator = Evaluator(pair, dataclasses.replace(settings))
    shared = FlankModification(25e-6, 5e-6)
    figures = fe_state_figures(evaluator, coarse_compliance, shared, 16, "aligned")
    assert set(figures) == set(STATE_FIGURES["aligned"])
    flanks = RealFlanks.from_config(shared.to_config(), {})
    ltca = fe_loaded_tca(MeshContact(pair, ContactParameters(model="line"),
                                     separation=flanks.separation(pair)),
                         coarse_compliance, 480.0, phases=16)
    assert figures["rated_transmission_error"] == pytest.approx(
        float(np.ptp(ltca["transmission_error"].values)), rel=1e-6)
    assert figures["contact_pressure"] == pytest.approx(
        float(ltca["max_flank_pressure"].max()), rel=1e-6)
    # over the load range, half the torque included: at least the rated torque's
    assert figures["transmission_error"] >= figures["rated_transmission_error"]
