"""The cutter-radius sweep in the workflow: the jobs the default, tiny and cluster studies plan."""

from tests.workflow.helpers import REPO, SNAKEFILE, TEST_CONFIG, planned_jobs, snakemake


def cutter_jobs(tmp_path, *configfiles):
    args = ["--configfile", *configfiles] if configfiles else []
    proc = snakemake("-n", "--snakefile", SNAKEFILE, *args, cwd=tmp_path, check=True)
    jobs = planned_jobs(proc.output)
    return {out for rule, out in jobs if rule.startswith("cutter_")}, proc.output


def test_default_study_sweeps_the_fitting_nominal_cutters_and_the_matched_one(tmp_path):
    outputs, text = cutter_jobs(tmp_path)
    assert outputs == {"results/cutter/lsbg.nc",
                       *(f"results/cutter/face_milled_r{r}.nc"
                         for r in ("44.45", "63.5", "76.2", "95.25", "114.3", "127.581"))}
    # the sweep report reads every point
    report = text[text.index("rule report_sweep:"):]
    report = report[:report.index("\n\n")]
    assert all(out in report for out in outputs)
    # the LSBG's and the design's SBG's FE loaded TCA are the study's own (results/tooth/)
    lsbg = text[text.index("rule cutter_lsbg:"):]
    assert "results/tooth/logarithmic_beta35_ltca.nc" in lsbg[:lsbg.index("\n\n")]


def test_tiny_and_cluster_studies_choose_their_cutters(tmp_path):
    outputs, _ = cutter_jobs(tmp_path, str(REPO / TEST_CONFIG))
    assert outputs == {"results/cutter/lsbg.nc", "results/cutter/face_milled_r76.2.nc",
                       "results/cutter/face_milled_r95.25.nc", "results/cutter/face_milled_r127.581.nc"}
    outputs, text = cutter_jobs(tmp_path, str(REPO / "workflow" / "config-cutter-cluster.yaml"))
    assert len(outputs) == 1 + 7 + 1  # the LSBG, every nominal cutter, the matched one
    assert "rule sweep_cutter_radius_combine:" in text


def test_a_bad_cutter_radius_stops_the_study_before_any_job(tmp_path):
    (tmp_path / "bad.yaml").write_text("cutter_sweep:\n  radii_mm: [76.2, 20]\n")
    proc = snakemake("-n", "--snakefile", SNAKEFILE, "--configfile", "bad.yaml", cwd=tmp_path)
    assert proc.returncode != 0
    assert "config key cutter_sweep.radii_mm[1] = 20: cannot span the face" in proc.output
