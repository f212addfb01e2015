"""The trace study's cells and the trace-level verdict (lsbg.optimise.cells)."""

import copy
import math
from pathlib import Path

import numpy as np
import pytest
import yaml

from lsbg.config import merge_config
from lsbg.gear.cutter import fitting_radii
from lsbg.gear.design import GearPairDesign
from lsbg.optimise import cells, fronts
from lsbg.optimise.checks import search_estimate

from .test_fronts import OBJECTIVES, converged_dataset, synthetic_front

REPO = Path(__file__).resolve().parents[2]


def study(*names, **trace_study):
    config = yaml.safe_load((REPO / "workflow" / "config.yaml").read_text(encoding="utf-8"))
    for name in names:
        config = merge_config(config, yaml.safe_load(
            (REPO / "workflow" / name).read_text(encoding="utf-8")))
    config = copy.deepcopy(config)
    config.setdefault("practice", {}).setdefault("sbg_trace", "face_milled")
    config.setdefault("cutter_sweep", {}).setdefault("usual_range_outer_cone_distance",
                                                     [0.5, 1.5])
    config["trace_study"] = trace_study
    return config


def test_the_default_study_has_the_paper_cell_only():
    (cell,) = cells.trace_cells(study())
    assert cell["label"] == "beta35" and cell["paper"] and cell["cutter_mm"] is None
    assert cell["spiral_angle"] == pytest.approx(math.radians(35))
    assert cell["lsbg_cell"] == "beta35"


def test_sweep_by_sweep_is_every_angle_by_every_fitting_cutter():
    config = study(spiral_angles_deg="sweep", cutter_radii_mm="sweep")
    got = cells.trace_cells(config)
    assert got[0]["paper"] and got[0]["label"] == "beta35"
    assert len({c["label"] for c in got}) == len(got)
    expected = 0
    for angle in config["sweep"]["spiral_angles_deg"]:
        design = GearPairDesign.from_config({**config["design"], "trace": "face_milled",
                                             "spiral_angle_deg": angle})
        radii = fitting_radii(design, "face_milled", (0.5, 1.5))
        at = [c for c in got if c["spiral_deg"] == angle]
        assert len(at) == len(radii)
        # the design's own cutter (76.2 mm) is the angle's cell of the design's cutter
        assert any(c["cutter_mm"] is None for c in at) == any(abs(r - 0.0762) < 1e-9
                                                              for r in radii)
        assert all(c["lsbg_cell"] == f"beta{c['spiral']}" for c in at)
        expected += len(radii)
    assert len(got) == expected > len(config["sweep"]["spiral_angles_deg"])


def test_an_explicit_list_gives_its_cells_in_order_paper_first():
    got = cells.trace_cells(study(spiral_angles_deg=[25, 35], cutter_radii_mm=[95.25, 76.2]))
    assert [c["label"] for c in got] == ["beta35", "beta25_r95.25", "beta25", "beta35_r95.25"]
    assert got[1]["cutter_radius"] == pytest.approx(0.09525)


def test_bad_cells_are_named_with_their_key_and_value():
    assert cells.trace_study_problems(study(spiral_angles_deg=[25, 45])) == []
    (line,) = cells.trace_study_problems(study(spiral_angles_deg=[25, 34]))
    assert line.startswith("trace_study.spiral_angles_deg[1] = 34: not the paper's angle")
    (line,) = cells.trace_study_problems(study(cutter_radii_mm=[23]))
    assert line.startswith("trace_study.cutter_radii_mm[0] = 23: at 35 deg cannot span")


def test_the_estimate_counts_every_cell_and_the_lsbg_once_per_angle():
    one = search_estimate(study())
    config = study(spiral_angles_deg=[25, 35], cutter_radii_mm=[95.25, 76.2])
    jobs, hours = search_estimate(config)
    seeds = 3  # (the default)
    # 2 angles: the LSBG at each, the SBG at 2 cutters each
    assert one[0] == 2 * seeds and jobs == (2 + 4) * seeds
    assert hours == pytest.approx(one[1] * jobs / one[0])


@pytest.mark.parametrize("verdicts, side, counts", [
    ([1, 1, 1], 1, (3, 0, 0, 0)),
    ([-1, -1], -1, (0, 2, 0, 0)),
    ([1, 1, -1], 0, (2, 1, 0, 0)),
    ([1, 0, 1], 0, (2, 0, 1, 0)),
    ([1, math.nan], 0, (1, 0, 0, 1)),
    ([0], 0, (0, 0, 1, 0)),
    ([-1], -1, (0, 1, 0, 0))])
def test_a_trace_is_better_only_where_it_is_in_every_cell(verdicts, side, counts):
    got = cells.trace_level_verdict({f"c{k}": v for k, v in enumerate(verdicts)})
    assert got["verdict"] == side and got["decided"] == bool(side)
    assert tuple(got["counts"][k] for k in ("lsbg", "sbg", "tie", "none")) == counts
    assert got["cells"] == len(verdicts)
    if not side:
        assert got["text"].startswith("not decided") and f"of {len(verdicts)} cells" in got["text"]


def test_the_verdict_of_constructed_fronts_per_cell():
    """Cells of datasets (lsbg trace-fronts'): the LSBG's fronts below the SBG's in one cell
    and above in another is not decided; below in both, the LSBG better."""
    rng = np.random.default_rng(7)

    def cell(lsbg_shift, sbg_shift):
        a = [synthetic_front(rng, lsbg_shift) for _ in range(3)]
        b = [synthetic_front(rng, sbg_shift) for _ in range(3)]
        stats = fronts.trace_statistics(a, b, OBJECTIVES)
        return fronts.trace_fronts_dataset(stats, converged_dataset("logarithmic", a, [1, 2, 3]),
                                           converged_dataset("face_milled", b, [1, 2, 3]))

    better, worse = cell(0.0, 0.3), cell(0.3, 0.0)
    assert float(better["verdict"]) == 1 and float(worse["verdict"]) == -1
    assert cells.trace_level_verdict({"beta25": better, "beta35": cell(0.0, 0.4)})["verdict"] == 1
    mixed = cells.trace_level_verdict({"beta25": better, "beta35": worse})
    assert mixed["verdict"] == 0 and mixed["counts"]["lsbg"] == mixed["counts"]["sbg"] == 1


def test_no_cell_or_a_bad_code_is_refused():
    with pytest.raises(ValueError, match="no cell"):
        cells.trace_level_verdict({})
    with pytest.raises(ValueError, match="not a verdict"):
        cells.trace_level_verdict({"beta35": 2})


def test_the_reports_table_has_a_row_per_cell_and_the_answer_over_them():
    from lsbg.tables.optimise import trace_cells_table, trace_level_text

    rng = np.random.default_rng(8)

    def cell(shift, angle, cutter):
        a = [synthetic_front(rng, 0.0) for _ in range(3)]
        b = [synthetic_front(rng, shift) for _ in range(3)]
        second = converged_dataset("face_milled", b, [1, 2, 3])
        second.attrs.update(design_spiral_angle_deg=angle, design_cutter_radius_mm=cutter)
        return fronts.trace_fronts_dataset(fronts.trace_statistics(a, b, OBJECTIVES),
                                           converged_dataset("logarithmic", a, [1, 2, 3]),
                                           second)

    datasets = [cell(0.3, 35.0, 76.2), cell(-0.3, 25.0, 95.25)]
    assert datasets[1].attrs["cell_cutter_radius_mm"] == 95.25
    table = trace_cells_table(datasets)
    assert table["cell"].tolist() == ["35 deg, r_c0 76.2 mm", "25 deg, r_c0 95.25 mm"]
    assert table["verdict"].str.startswith(("the LSBG", "the SBG")).tolist() == [True, True]
    assert table["A12"].tolist() == [1.0, 0.0]
    text = trace_level_text(datasets)
    assert "not decided: the LSBG better in 1, the SBG in 1" in text and "Indicative" in text
    assert "better in all 2 cells" in trace_level_text([datasets[0], cell(0.4, 25.0, 95.25)])


def test_the_cluster_configuration_runs_what_its_header_and_docs_scaling_say():
    from lsbg.config import SCHEMA_PATH, load_schema
    from lsbg.study.checks import fill_defaults

    config = study("config-trace.yaml")
    config["trace_study"] = yaml.safe_load((REPO / "workflow" / "config-trace.yaml").read_text(
        encoding="utf-8"))["trace_study"]
    fill_defaults(config, load_schema(SCHEMA_PATH))
    got = cells.trace_cells(config)
    assert len(got) == 55 and len({c["spiral"] for c in got}) == 11
    jobs, hours = search_estimate(config)
    assert jobs == 330 and hours == pytest.approx(56.3, abs=0.05)
