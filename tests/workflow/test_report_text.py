"""The reports say what ran: design values, loads and angles from the study's files.

The session's study (tests/workflow/conftest.py, the test configuration: one spiral
angle, the paper's pair) and a pair with another face width in a study folder of its
own (run by a copy of the repository of its own); a load sweep on top of a copy of the
session's study is named in the paper report (tests/workflow/test_workflow.py, the load
sweep's test).
"""

import pytest

from tests.workflow.helpers import (TEST_CONFIG, report_text, repository_with_env,
                                    snakemake, write_yaml)


def first_screen(text):
    return text[text.index("Compared"):][:2500]


@pytest.mark.slow
def test_one_spiral_angle_and_the_papers_pair(study):
    root, _ = study
    paper, sweep = (report_text(root / "reports" / f"{n}.html") for n in ("paper", "sweep"))
    assert ("of the paper's Table 1 (9:37 teeth, module 4.5 mm, spiral angle 35°; face width "
            "25 mm)") in first_screen(paper)
    assert "gear loaded with 1964.99 N·m" in first_screen(paper)
    assert "No other load was run" in paper
    # one angle ran: no statement across angles
    assert "at one spiral angle, 35°" in first_screen(sweep)
    assert "depends on the spiral angle" not in sweep and "35–35" not in sweep
    assert "spiral angles" not in first_screen(sweep).split("(compiled engine)")[0]
    # the test configuration is coarse: every report says so first; no nan, None or empty
    # cell anywhere (a type that keeps the shared ease-off says so, not "nan %")
    from tests.test_reports import report_leaks

    for name in ("paper", "sweep", "verification"):
        html = (root / "reports" / f"{name}.html").read_text(encoding="utf-8")
        assert report_leaks(html) == [], name
        assert "Coarse configuration: the numbers of this report are not the study's" in html
        assert html.index('class="lsbg-coarse"') < html.index("<h2")
    assert paper.index("the paper's claim as published") < paper.index("Compared")
    # the practice and best pairs' claims in the published pair's cells (the test
    # configuration's five cases, practice.sensitivity: [all]), the point model aside
    for heading, cells in (("The practice design's stability claim", 7),
                           ("The practice design's contact state claim", 2),
                           ("Best against best: the stability claim", 7),
                           ("Best against best: the service life claim", 12)):
        assert f"{heading} at " in paper, heading
        assert f"in each of its {cells} model-form cells" in \
            paper[paper.index(heading):][:300], heading
    section = paper[paper.index("The practice design's stability claim"):]
    for case in ("damping ratio ×2", "compliance: FE", "crowning ×0.5", "500-Hz sampling",
                 "pinion speed ×1.5", "boundary: torsional driveline"):
        assert case in section[:section.index("The practice design's contact state claim")]
    import xarray as xr

    for release in sorted((root / "results" / "optimise").glob("*_release.nc")):
        with xr.open_dataset(release) as ds:
            if int(ds.attrs["chosen"]) < 0:
                assert "% (it keeps the shared ease-off)" in paper
                assert "the shared ease-off stays" in paper


@pytest.mark.slow
def test_another_face_width_is_stated_as_a_change(tmp_path):
    """A study of its own (-d): the face width 30 mm, stated as a change from Table 1 in
    the paper and sweep reports; the design values the reports name are the ones that ran.
    It runs the Snakefile of a fresh copy of the repository, not the session's study, so
    that it can run on the other worker; the copy must stay without results. Without the practice
    design and without any sensitivity cell, which the schema allows: the reports must
    render without them (the paper report's service-life section once failed there)."""
    root, env = repository_with_env(tmp_path / "repository")
    mine = tmp_path / "face30"
    mine.mkdir()
    # (the practice design and the sensitivity cells left out: the session's study renders them)
    no_cells = {key: [] for key in ("mesh_damping_ratio", "line_stiffness_N_per_mm_um",
                                    "slices", "compliance", "crowning", "displacement")}
    config = write_yaml(mine / "config.yaml", {"design": {"face_width_mm": 30},
                                               "practice": {"enabled": False},
                                               "sensitivity": no_cells})
    # The two reports that state the design (the verification report names none): what
    # they read, not the whole study (the verification report's CPU, about 6 s, less).
    snakemake("-j2", "reports/paper.html", "reports/sweep.html", "-s", root / "Snakefile",
              "-d", mine, "--configfile", root / TEST_CONFIG, config, cwd=tmp_path, env=env,
              check=True)
    paper, sweep = (report_text(mine / "reports" / f"{n}.html") for n in ("paper", "sweep"))
    for text in (paper, sweep):
        assert "modified from the paper's Table 1" in first_screen(text)
        assert "face width 30 mm" in first_screen(text)
        assert "25-mm" not in text and "face width 25 mm" not in text
    assert "face width 30 mm" in paper[paper.index("Where the study's load stands"):][:400]
    assert "displacement envelope (this study ran none of them)" in paper
    # Table 1: only the face width's row is changed, each other row of the paper's says so
    assert "face width b mm changed (assumed: 25) 30" in paper
    assert "changed (paper:" not in paper
    assert "number of teeth z1 (pinion) - paper Table 1 9 9" in paper
    # and the repository whose Snakefile ran is untouched
    assert not [name for name in ("results", "logs", "reports", ".snakemake")
                if (root / name).exists()]
