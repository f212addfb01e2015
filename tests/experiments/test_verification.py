"""Convergence study and per-step cost of the engines (short runs)."""

import numpy as np
import pandas as pd
import pytest

from lsbg.gear.design import GearPairDesign
from lsbg.dynamics import SimulationSettings, load_model
from lsbg.solid.export import write_geometry
from lsbg.experiments.verification import COLUMNS, convergence_study, pybullet_step_costs


@pytest.fixture(scope="module")
def model(tmp_path_factory):
    out = tmp_path_factory.mktemp("lsbg") / "geometry"
    write_geometry(GearPairDesign(), out)
    return load_model(out)


SHORT = SimulationSettings(duration=0.03, samples=30, ramp_time=0.01)


def test_convergence_table_has_every_setting(model):
    table = convergence_study(model, SHORT, steady_start=0.01, time_steps=(2e-6, 1e-6),
                              tolerances=(1e-6, 1e-8))
    assert list(table.columns) == list(COLUMNS)
    assert list(table.engine) == ["pybullet", "pybullet", "scipy", "scipy", "compiled", "compiled"]
    assert table.is_default.sum() == 3
    assert set(table.contact_model) == {"point"}
    assert (table.gear_speed_std_deg_s > 0).all()
    # the finer settings of each engine agree with each other closely
    fine = table[table.is_default]
    stds = fine.tangential_force_std_N.to_numpy()
    assert stds[0] == pytest.approx(stds[1], rel=0.05)


def test_step_cost_breakdown(model):
    costs = pybullet_step_costs(model, SHORT, n=2000, repeats=3)
    assert set(costs) == {"joint_states", "contact_kernel", "apply_torque", "motor_target",
                          "step_simulation", "floor_steady", "floor_ramp", "floor",
                          "engine_step", "ramp_share", "engine_over_floor"}
    assert all(v > 0 for v in costs.values())
    assert costs["ramp_share"] == pytest.approx(SHORT.ramp_time / SHORT.duration)
    # Timings on a shared machine jitter by tens of percent, so only gross
    # relations are checked: the floor is made of the parts, and the engine
    # does the floor's calls and a kernel call more.
    assert costs["floor_steady"] > 0.5 * (costs["joint_states"] + costs["apply_torque"]
                                          + costs["step_simulation"])
    assert 0.5 < costs["engine_over_floor"] < 10.0


def test_setting_label_reads_as_words():
    from lsbg.tables.verification import setting_label

    assert setting_label("pybullet", "time_step_s", 1e-6, True) == "pybullet dt = 1 µs (default)"
    assert setting_label("pybullet", "time_step_s", 4e-6) == "pybullet dt = 4 µs"
    assert setting_label("compiled", "rtol", 1e-8) == "compiled rtol = 10⁻⁸"
    assert setting_label("scipy", "rtol", 3e-7) == "scipy rtol = 3×10⁻⁷"


def test_convergence_display_is_narrow_and_keeps_the_numbers():
    import pandas as pd

    from lsbg.tables.verification import (CONVERGENCE_DISPLAY_COLUMNS, by_gear_type,
                                          convergence_display)

    table = pd.DataFrame({
        "trace": ["logarithmic", "circular"], "spiral_angle_deg": [35.0, 35.0],
        "contact_model": ["point", "point"], "engine": ["pybullet", "compiled"],
        "parameter": ["time_step_s", "rtol"], "value": [2e-6, 1e-8],
        "is_default": [False, True], "gear_speed_mean_deg_s": [1873.7, 1873.8],
        "steps": [500000, 103850], "reference": ["compiled rtol 1e-08"] * 2,
        **{c: [float(i), float(i) + 0.5] for i, c in enumerate(CONVERGENCE_DISPLAY_COLUMNS)}},
        index=[7, 3])
    shown = convergence_display(table)
    assert list(shown.columns) == ["gear_type", "setting", *CONVERGENCE_DISPLAY_COLUMNS]
    assert list(shown.gear_type) == ["LSBG", "SBG"]
    assert list(shown.setting) == ["pybullet dt = 2 µs", "compiled rtol = 10⁻⁸ (default)"]
    for column in CONVERGENCE_DISPLAY_COLUMNS:
        assert list(shown[column]) == list(table[column])

    checks = pd.DataFrame({"gear_type": ["LSBG", "SBG"], "a_rad": [1.0, 2.0],
                           "b_percent": [3.0, 4.0]})
    turned = by_gear_type(checks, [("a_rad", "first", "rad"), ("b_percent", "second", "%")])
    assert list(turned.columns) == ["check", "unit", "SBG", "LSBG"]
    assert list(turned.SBG) == [2.0, 4.0] and list(turned.LSBG) == [1.0, 3.0]
    assert list(turned.unit) == ["rad", "%"]


def test_convergence_reference_is_the_tightest_tolerance():
    """rtol 1e-8 and 1e-10 are different settings (np.isclose's default atol had made them equal)."""
    from lsbg.tables.verification import convergence_table

    rows = [{"trace": "logarithmic", "spiral_angle_deg": 35.0, "contact_model": "line",
             "engine": engine, "parameter": "rtol", "value": rtol,
             "gear_speed_std_deg_s": std, "tangential_force_std_N": 10 * std,
             "gear_speed_full_std_deg_s": std, "tangential_force_full_std_N": 10 * std}
            for engine, rtol, std in (("compiled", 1e-6, 1.2), ("compiled", 1e-8, 1.1),
                                      ("compiled", 1e-10, 1.0), ("scipy", 1e-8, 1.05))]
    table = convergence_table(pd.DataFrame(rows))
    assert set(table.reference) == {"compiled rtol 1e-10"}
    assert np.allclose(table.gear_speed_std_rel_diff_percent, [20, 10, 0, 5])
