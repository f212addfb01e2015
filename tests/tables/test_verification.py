"""lsbg.tables.verification.verification_checks: the engines' checks against their own
integration errors (the design point's checks: tests/experiments/test_point_checks.py)."""

import numpy as np
import pandas as pd
import pytest

from lsbg.experiments.point_checks import peak_to_peak_resolution
from lsbg.experiments.verification import COLUMNS
from lsbg.tables import verification as verification_tables


def convergence(pybullet=100.0, order=1, scipy=100.0):
    """A point-model and a line-model convergence study of the LSBG: the compiled engine
    converging to a std of 100 as rtol^0.7, PyBullet to ``pybullet`` at ``order`` in the
    step (3 % off at 1 µs), scipy to ``scipy``."""
    rows = []
    for model, engines in (("point", ("pybullet", "compiled")), ("line", ("scipy", "compiled"))):
        for engine in engines:
            settings = ((4e-6, 2e-6, 1e-6) if engine == "pybullet" else (1e-6, 1e-8, 1e-10))
            for value in settings:
                if engine == "pybullet":
                    std = pybullet * (1 + 0.03 * (value / 1e-6)**order)
                else:
                    std = (scipy if engine == "scipy" else 100.0) * (1 + 0.1 * value**0.7)
                rows.append({"trace": "logarithmic", "spiral_angle_deg": 35.0,
                             "contact_model": model, "engine": engine,
                             "parameter": "time_step_s" if engine == "pybullet" else "rtol",
                             "value": value,
                             "is_default": value == (1e-6 if engine == "pybullet" else 1e-8),
                             "gear_speed_mean_deg_s": 1870.0, "gear_speed_std_deg_s": std,
                             "tangential_force_mean_N": 26000.0,
                             "tangential_force_std_N": 70 * std, "gear_speed_full_std_deg_s": std,
                             "tangential_force_full_std_N": 70 * std, "wall_time_s": 1.0,
                             "steps": 1000})
    return verification_tables.convergence_table(pd.DataFrame(rows, columns=list(COLUMNS)))


def agreement(table):
    """The engines' agreement at the defaults, as agreement_by_model gives it."""
    default = table[table.is_default].set_index(["contact_model", "engine"])
    rows = [{"gear_type": "LSBG", "contact_model": model, "engine": engine,
             "reference": "compiled", "quantity": "gear_speed",
             "std_ratio": default.loc[(model, engine), "gear_speed_std_deg_s"]
             / default.loc[(model, "compiled"), "gear_speed_std_deg_s"]}
            for model, engine in (("point", "pybullet"), ("line", "scipy"))]
    return pd.DataFrame(rows)


def engine_checks(table):
    """The engines' rows of verification_checks (no design point's checks)."""
    checks = verification_tables.verification_checks({}, {}, {}, table, agreement(table))
    assert (checks.unit == "%").all() and (checks.reason.str.len() > 20).all()
    return checks.set_index("key")


def test_engines_converging_to_the_reference_pass_within_their_errors():
    checks = engine_checks(convergence())
    assert list(checks.index) == ["pybullet_point", "compiled", "agreement"]
    assert checks["pass"].all(), checks
    # PyBullet is 3 % off at 1 µs; Richardson from 2 µs says so (first order)
    assert checks.loc["pybullet_point", "value"] == pytest.approx(3.0, rel=1e-6)
    assert checks.loc["pybullet_point", "bound"] == pytest.approx(3.0, rel=1e-3)
    # a method of higher order than the estimate assumes is inside it with room
    assert engine_checks(convergence(order=2)).loc["pybullet_point"].pipe(
        lambda r: r["pass"] and r.value < 0.4 * r.bound)


@pytest.mark.parametrize("planted, key", [
    (dict(pybullet=101.0), "pybullet_point"),   # converging to another answer: 1 % off
    (dict(scipy=100.5), "agreement"),           # scipy's line model 0.5 % off the compiled
])
def test_an_engine_converging_elsewhere_fails(planted, key):
    checks = engine_checks(convergence(**planted))
    assert not checks.loc[key, "pass"], checks


def test_without_the_coarser_run_there_is_no_bound():
    table = convergence()
    table = table[~((table.engine == "pybullet") & (table.value > 1.5e-6))]
    checks = engine_checks(table)
    assert np.isnan(checks.loc["pybullet_point", "bound"])
    assert not checks.loc["pybullet_point", "pass"]


def test_peak_to_peak_resolution_covers_the_sampling_error():
    fine = np.linspace(0.0, 1.0, 100000, endpoint=False)
    smooth = np.sin(2 * np.pi * fine) + 0.3 * np.sin(6 * np.pi * fine + 1)
    cusps = 4 * ((fine + 0.37) % 1 - 0.5)**2   # convex arcs meeting in a cusp
    for curve, at_cusps in ((smooth, False), (cusps, True)):
        for n in (16, 40, 100, 256):
            for offset in range(0, 1000, 97):
                sampled = curve[offset::100000 // n][:n]
                error = np.ptp(curve) - np.ptp(sampled)
                assert 0 <= error <= peak_to_peak_resolution(sampled, at_cusps) + 1e-12


def spiral_rows(trace, **design):
    """The spiral-angle row of verification_checks from a design point's record."""
    from lsbg.gear.design import GearPairDesign
    from lsbg.gear.geometry import GearPair
    from lsbg.solid.export import design_record

    record = design_record(GearPair(GearPairDesign(trace=trace, **design)))
    checks = verification_tables.verification_checks({}, {}, {"SBG": record})
    return checks[checks.key == "spiral_SBG"].iloc[0], record


def test_the_face_milled_sbgs_spiral_angle_is_checked_at_every_cone_distance():
    """ISO 23509's closed form at each of the record's cone distances, not its spread."""
    row, record = spiral_rows("face_milled")
    assert row["pass"] and row["value"] < 1e-6 < 0.01
    assert "at every R" in row["reason"]
    # a record whose heel is off by 0.01 deg fails, though its toe and mean are right
    record["spiral_angle_along_face_deg"][-1] += 0.01
    checks = verification_tables.verification_checks({}, {}, {"SBG": record})
    assert not checks[checks.key == "spiral_SBG"].iloc[0]["pass"]


def test_the_papers_arc_is_checked_against_its_own_closed_form():
    row, _ = spiral_rows("circular")
    assert row["pass"] and "tan β = tan β_p(ρ)/cos γ" in row["reason"]
