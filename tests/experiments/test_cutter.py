"""The cutter-radius sweep's points and checks (lsbg.experiments.cutter)."""

import copy
from pathlib import Path

import pytest
import yaml

from lsbg.experiments.cutter import cutter_points
from lsbg.study import checks as config_check

REPO = Path(__file__).resolve().parents[2]
SCHEMA = yaml.safe_load((REPO / "lsbg" / "schemas" / "config.schema.yaml").read_text())


@pytest.fixture(scope="module")
def default():
    config = yaml.safe_load((REPO / "workflow" / "config.yaml").read_text())
    assert config_check.check_config(config, SCHEMA, analyses=False) == []
    return config


def with_cutter(config, **section):
    changed = copy.deepcopy(config)
    changed["cutter_sweep"] = {**changed["cutter_sweep"], **section}
    return changed


def test_default_points_are_the_lsbg_the_fitting_nominal_cutters_and_the_matched_one(default):
    points = cutter_points(default)
    assert points[0]["label"] == "lsbg" and points[0]["trace"] == "logarithmic"
    assert points[0]["radius_mm"] == pytest.approx(127.58, abs=0.01)  # R_m / sin(beta_m)
    sbg = points[1:]
    assert [p["radius_mm"] for p in sbg] == sorted(p["radius_mm"] for p in sbg)
    assert [p["radius_mm"] for p in sbg if "nominal" in p["roles"]] == [
        44.45, 63.5, 76.2, 95.25, 114.3]
    (design,) = [p for p in sbg if "design" in p["roles"]]
    assert design["radius_mm"] == default["design"]["cutter_radius_mm"]
    (matched,) = [p for p in sbg if "matched" in p["roles"]]
    # ISO 23509's cutter circle is the developed pitch cone's trace: the matched cutter is
    # the LSBG's R_m / sin(beta_m) itself
    assert matched["radius_mm"] == pytest.approx(points[0]["radius_mm"], rel=1e-5)
    # lsbg's arc in the plane of action curves tighter on the pitch cone: 135.77 mm
    (arc,) = [p for p in cutter_points(with_cutter(default, trace="circular"))
              if "matched" in p["roles"]]
    assert 130 < arc["radius_mm"] < 140
    # the FE stresses at the decomposition's points only (and the LSBG's, from the study)
    assert [p["label"] for p in points if p["fe"]] == ["lsbg", "r76.2", matched["label"]]
    assert len({p["label"] for p in points}) == len(points)


def test_listed_radii_and_the_fe_choice(default):
    points = cutter_points(with_cutter(default, radii_mm=[95.25], fe="all"))
    assert [p["radius_mm"] for p in points[1:] if "nominal" in p["roles"]] == [95.25]
    # the design's cutter and the matched one join a listed sweep
    assert {"design", "matched"} <= {r for p in points for r in p["roles"]}
    assert all(p["fe"] for p in points)
    assert not any(p["fe"] for p in cutter_points(with_cutter(default, fe="none")))


def test_bad_radii_are_named_by_key_and_value_before_any_job(default):
    problems = config_check.check_config(with_cutter(default, radii_mm=[76.2, 20, 300]),
                                         SCHEMA, analyses=False)
    assert len(problems) == 2
    assert problems[0].startswith("cutter_sweep.radii_mm[1] = 20: cannot span the face")
    assert problems[1].startswith("cutter_sweep.radii_mm[2] = 300: is outside the usual")
    (line,) = config_check.check_config(
        with_cutter(default, usual_range_outer_cone_distance=[1.5, 0.5]), SCHEMA,
        analyses=False)
    assert line.startswith("cutter_sweep.usual_range_outer_cone_distance = [1.5, 0.5]")
    (line,) = config_check.check_config(with_cutter(default, radii_mm=[-5]), SCHEMA,
                                        analyses=False)
    assert "cutter_sweep.radii_mm" in line
    # a disabled sweep is not checked
    assert config_check.check_config(with_cutter(default, enabled=False, radii_mm=[20]),
                                     SCHEMA, analyses=False) == []
