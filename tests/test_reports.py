"""The report notebooks execute on short real runs and render to self-contained HTML."""

import math
import re
import shutil
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import xarray as xr

from lsbg import cli, reports
from lsbg.experiments import speed
from lsbg.aggregate.combine import combine_runs
from lsbg.aggregate.runs import open_pair, steady
from lsbg.aggregate.summary import summary_table
from lsbg.contact import ContactParameters
from lsbg.gear.design import GearPairDesign
from lsbg.dynamics import SimulationSettings, load_model, simulate
from lsbg.solid.export import write_geometry
from lsbg.tca.loaded import ltca_for_geometry
from lsbg.files import write_dataset
from lsbg.experiments.verification import convergence_study

#: One worker takes the module (``-n 2 --dist loadgroup``): split over both, each built
#: :func:`study_files` (about 14 s).
pytestmark = pytest.mark.xdist_group("reports")

SHORT = SimulationSettings(duration=0.05, samples=25, ramp_time=0.01)
# windows that fit 0.05 s: 20 samples after 0.01 s, 4 subgroups of 5
STATISTICS = dict(steady_state_after_s=0.01, chart_window_start_s=0.01,
                  chart_window_stop_s=0.05, subgroup_size=5)


@pytest.fixture(scope="module")
def study_files(tmp_path_factory):
    """Geometry, runs (both contact models; pybullet, scipy and compiled), loaded TCAs,
    a sensitivity case, the sweep, the summary and convergence tables."""
    root = tmp_path_factory.mktemp("reports")
    files = {"root": root, "geometry": {}, "runs": {}, "meshes": {}, "sensitivity": []}
    line = ContactParameters(model="line")
    for trace in ("logarithmic", "circular"):
        geometry = root / "results" / "geometry" / f"{trace}_beta35"
        write_geometry(GearPairDesign(trace=trace), geometry)
        files["geometry"][trace] = geometry
        for model, params in (("point", ContactParameters()), ("line", line)):
            for engine in ("pybullet", "scipy", "compiled"):
                path = root / "results" / "runs" / f"{trace}_beta35_{model}_{engine}.nc"
                write_dataset(simulate(geometry, SHORT.replace(engine=engine), params), path)
                files["runs"][(trace, model, engine)] = path
        files["meshes"][trace] = root / "results" / "mesh" / f"{trace}_beta35.nc"
        write_dataset(ltca_for_geometry(geometry, 1964.99, phases=64), files["meshes"][trace])
        path = root / "results" / "sensitivity" / f"{trace}_beta35_mesh_damping_ratio_x2.nc"
        write_dataset(simulate(geometry, SHORT.replace(engine="compiled"),
                               line.replace(damping_ratio=0.1)), path)
        files["sensitivity"].append(path)
    compiled = [files["runs"][(t, m, "compiled")] for t in ("logarithmic", "circular")
                for m in ("point", "line")]
    files["sweep"] = root / "results" / "sweep.nc"
    write_dataset(combine_runs(compiled, meshes=list(files["meshes"].values())),
                  files["sweep"])
    files["summary"] = root / "results" / "summary.csv"
    summary_table([*files["runs"].values(), *files["sensitivity"]], steady_state_after=0.01,
                        window=(0.01, 0.05), subgroup_size=5,
                        meshes=list(files["meshes"].values())).to_csv(files["summary"], index=False)
    speed_runs = []
    for trace in ("logarithmic", "circular"):
        for omega in (40000.0, 73000.0, 120000.0):
            settings = speed.speed_settings(SHORT.replace(engine="compiled"), math.radians(omega),
                                            9, mesh_cycles=20, min_window=0.01,
                                            settle_time=0.02, ramp_time=0.02)
            speed_runs.append(simulate(files["geometry"][trace], settings, line))
    files["speed_curve"] = root / "results" / "speed_curve.nc"
    write_dataset(speed.speed_curve(speed_runs), files["speed_curve"])
    # the contact state: crowned flanks, a small V-H map per type (lsbg misalignment-map)
    files["tca"], files["vh"] = [], []
    for trace in ("logarithmic", "circular"):
        tca = root / "results" / "tca" / f"{trace}_beta35.nc"
        vh = root / "results" / "vh" / f"{trace}_beta35.nc"
        assert cli.main(["misalignment-map", "--geometry", str(files["geometry"][trace]),
                         "--set", "flank_modification.lengthwise_crowning_um=25",
                         "--set", "flank_modification.profile_crowning_um=5",
                         "--set", "misalignment_map.steps=3",
                         "--set", "misalignment_map.positions=24",
                         "--set", "misalignment_map.load_torque_N_m=500", "--out", str(vh),
                         "--tca-out", str(tca)]) == 0
        files["tca"].append(tca)
        files["vh"].append(vh)
    files["convergence"] = []
    for model, params in (("point", ContactParameters()), ("line", line)):
        table = convergence_study(load_model(files["geometry"]["logarithmic"], params), SHORT,
                                  steady_start=0.01, time_steps=(2e-6, 1e-6),
                                  tolerances=(1e-6, 1e-8))
        path = root / "results" / "verification" / f"convergence_logarithmic_{model}.csv"
        path.parent.mkdir(parents=True, exist_ok=True)
        table.to_csv(path, index=False)
        files["convergence"].append(path)
    # what the reports show that a stage computes: the checks of each design point
    # (lsbg checks) and the ISO 10300 rating of every point of the summary (lsbg rate-sweep)
    files["checks"] = []
    for trace in ("logarithmic", "circular"):
        path = root / "results" / "verification" / f"{trace}_beta35_checks.nc"
        assert cli.main(["checks", "--geometry", str(files["geometry"][trace]),
                         "--mesh", str(files["meshes"][trace]),
                         "--run", str(files["runs"][(trace, "point", "pybullet")]),
                         "--out", str(path)]) == 0
        files["checks"].append(path)
    files["rating_sweep"] = root / "results" / "rating_sweep.nc"
    assert cli.main(["rate-sweep", "--summary", str(files["summary"]),
                     "--out", str(files["rating_sweep"])]) == 0
    return files


def paper_parameters(files):
    return {"runs": list(files["runs"].values()), "sensitivity_runs": files["sensitivity"],
            "mesh_files": list(files["meshes"].values()),
            "geometry_dirs": [files["geometry"][t] for t in ("logarithmic", "circular")],
            "paper_engine": "pybullet",
            "line_engine": "compiled", "sweep_file": files["sweep"], "tca_files": files["tca"],
            "vh_files": files["vh"], "checks_files": files["checks"], **STATISTICS}


def report_leaks(html):
    """What a report must never show: "nan", "None" or a placeholder in its text (figures,
    styles and attached files left out), or an empty table cell."""
    import html as markup

    page = re.sub(r"<(script|style)\b.*?</\1>", " ", html, flags=re.S)
    page = re.sub(r'(?:src|href)="data:[^"]*"', "", page)
    text = markup.unescape(re.sub(r"<[^>]+>", " ", page))
    words = [text[max(0, m.start() - 80):m.end() + 40]
             for m in re.finditer(r"\b(?:nan|NaN|None|TODO|XXX)\b|\{[a-z_]+\}", text)]
    empty = [c for c in re.findall(r"<td[^>]*>(.*?)</td>", page, re.S)
             if not re.sub(r"<[^>]+>|\s|&nbsp;", "", c)]
    return words + [f"{len(empty)} empty table cells"] * bool(empty)


def check_html(path, headings, images, code_snippets):
    """Headings present, ``images`` embedded PNGs, no code, nothing loaded from the network."""
    html = path.read_text(encoding="utf-8")
    for heading in headings:
        assert re.search(r"<h[1-3][^>]*>" + re.escape(heading), html), heading
    tags = re.findall(r"<img\b[^>]*>", html)
    assert len(tags) == images
    assert all('src="data:image/png;base64,' in tag for tag in tags)
    assert not re.search(r"<script[^>]*\bsrc=", html)
    assert not re.search(r"""(?:src|href)=["']https?://""", html)
    # inputs are excluded: no code cell input areas and none of the code itself
    assert not re.search(r'jp-CodeCell[^>]*>\s*<div class="jp-Cell-inputWrapper', html)
    assert 'class="jp-InputPrompt' not in html
    for snippet in code_snippets:
        assert snippet not in html
    assert "Traceback" not in html
    assert not [p for p in path.parent.iterdir() if p.name.startswith(".")]
    # the finding comes first, and headers are words, not code
    assert html.index('class="lsbg-finding"') < html.index("<h2")
    headers = [re.sub("<[^>]+>", "", h) for h in re.findall(r"<th[^>]*>(.*?)</th>", html, re.S)]
    assert headers and not [h for h in headers if re.search(r"[A-Za-z]_[A-Za-z]", h)]
    assert "&lt;NA&gt;" not in html and "urad" not in html
    assert report_leaks(html) == []
    return html


def embedded_csv(html):
    """The tables a report attaches as CSV links, by file name."""
    import base64
    import io

    return {name: pd.read_csv(io.BytesIO(base64.b64decode(data)))
            for name, data in re.findall(r'download="([^"]+)" href="data:text/csv;base64,([^"]+)"',
                                         html)}


def test_paper_report(study_files, tmp_path):
    out = tmp_path / "reports" / "paper.html"
    assert reports.render_report("paper", out, paper_parameters(study_files)) == out
    html = check_html(
        out, ["Logarithmic against conventional", "1. The design", "2. Input", "3. The gear",
              "4. The tangential contact force", "5. Normality", "6. Histograms",
              "7. Xbar-R control charts", "8. Simulated means", "9. The paper", "10. Which gear",
              "11. Agreement", "12. What the paper", "13. The line model",
              "14. Dynamics under the line model", "15. Claim 1, transmission stability",
              "16. Claim 2, the contact state", "17. The tooth itself", "18. Claim 3, service life",
              "19. The pair as a designer would make it",
              "20. Each type at its best ease-off", "21. Conclusion",
              "Appendix A. The summary statistics",
              "Appendix B. Inputs and settings"],
        # pair picture, Fig. 8, 9-10, 11, 12, 13, 14, 15 (2), 16, 17 (2), 18 (2); sampling
        # luck, spectrum, full-rate stretch; TE and stiffness, load sharing, contact
        # pattern; two spectra, full-rate stretch; sensitivity; bearing pattern,
        # unloaded TE, two V-H maps
        images=28, code_snippets=["select_runs(all_runs", "import numpy", 'rep = Report("paper")'])
    assert html.count("<b>Figure ") + html.count("<strong>Figure ") == 26
    # the contact state: its statement names the type whose pattern moves less, in the
    # finding and in Section 16, from the maps' own figures
    from lsbg.aggregate.runs import gear_type
    from lsbg.tables import contact_state

    maps = {}
    for path in study_files["vh"]:
        with xr.open_dataset(path) as ds:
            maps[gear_type(ds)] = ds.load()
    totals = {t: contact_state.pattern_movement(ds)["total"] for t, ds in maps.items()}
    steadier = min(totals, key=totals.get)
    # Section 16's statement; the claim's answer in the finding, Section 16 and the
    # conclusion, from its model-form table (here the baseline's cell alone)
    assert html.count(f"the <strong>{steadier}</strong>'s bearing pattern moves less") == 1
    assert html.count("<strong>Contact state</strong> (the LSBG's tooth contact state is better; "
                      "1 cell, Section 16)") == 2
    assert (f"bearing pattern's movement per 0.1 mm of displacement</strong> at 35°: the "
            f"<strong>{steadier}</strong> is lower in its only cell") in html
    assert "<strong>Answer (claim 1):</strong>" in html and "<strong>Answer (claim 2):</strong>" in html
    # no rating in this study: the third claim is said to be untested, not answered
    assert html.count("<strong>Service life</strong>: not tested by this study") == 2
    # numbers are computed from the runs
    runs = open_pair(study_files["runs"][("circular", "point", "pybullet")],
                           study_files["runs"][("logarithmic", "point", "pybullet")])
    sbg_std = steady(runs["SBG"], "gear_speed", 0.01).std(ddof=1)
    assert f"{sbg_std:.4g} deg/s (SBG)" in html
    assert "1283.8 rpm" in html and "24799.9" in html
    assert "the engines agree within 3 %" in html or "do NOT all agree" in html
    assert "<table" in html and "lsbg 0.1.0" in html
    # the line model's verdict: the loaded TCA and the sensitivity cells
    with xr.open_dataset(study_files["meshes"]["circular"]) as mesh:
        pp = mesh.attrs["transmission_error_peak_to_peak_urad"]
    assert f"{pp:.4g} µrad (SBG)" in html
    for cell in ("line model (baseline)", "point model", "damping ratio ×2", "500-Hz sampling"):
        assert cell in html
    assert "survives the model form" in html or "no ranking is stated" in html
    # the finding states the answer with its numbers and scopes it to this spiral angle
    finding = html[html.index('class="lsbg-finding"'):html.index("<h2", html.index("</div>", html.index('class="lsbg-finding"')))]
    assert "<strong>Stability</strong> (the LSBG's gear speed and contact force fluctuate less; " \
           "4 cells, Section 15)" in finding
    assert "std(SBG)/std(LSBG) " in finding and "at 35°" in finding
    assert "ran no other spiral angle" in finding
    # Appendix A recomputes the summary table's rows of this design point, attached in full
    table = pd.read_csv(study_files["summary"])
    assert '<td class="text">contact torque</td><td class="text">N·m</td>' in html
    (attached,) = embedded_csv(html).values()
    assert len(attached) == len(table)
    for row in table[table.engine != "ltca"].itertuples():
        match = attached[(attached.run == row.run) & (attached.quantity == row.quantity)]
        assert np.isclose(match.full_rate_std.iloc[0], row.full_rate_std, rtol=1e-12), row.run


def test_paper_report_of_a_30_degree_pair_names_the_change(tmp_path):
    """A study of one's own at 30° (the test configuration's pair, everything else as
    published, short runs): the report calls it a change from Table 1 in the finding and in
    Table 1's spiral-angle row alone, opens with the coarse banner and the verdict matrix,
    and shows no "nan", "None" or empty cell."""
    line = ContactParameters(model="line")
    runs, geometry, meshes, checks, sensitivity = [], [], [], [], []
    for trace in ("logarithmic", "circular"):
        directory = tmp_path / "results" / "geometry" / f"{trace}_beta30"
        write_geometry(GearPairDesign(trace=trace, spiral_angle=math.radians(30)), directory)
        geometry.append(directory)
        for model, params, engine in (("point", ContactParameters(), "pybullet"),
                                      ("point", ContactParameters(), "compiled"),
                                      ("line", line, "compiled")):
            path = tmp_path / "results" / "runs" / f"{trace}_beta30_{model}_{engine}.nc"
            write_dataset(simulate(directory, SHORT.replace(engine=engine), params), path)
            runs.append(path)
        sensitivity.append(tmp_path / "results" / "sensitivity"
                           / f"{trace}_beta30_mesh_damping_ratio_x2.nc")
        write_dataset(simulate(directory, SHORT.replace(engine="compiled"),
                               line.replace(damping_ratio=0.1)), sensitivity[-1])
        meshes.append(tmp_path / "results" / "mesh" / f"{trace}_beta30.nc")
        write_dataset(ltca_for_geometry(directory, 1964.99, phases=64), meshes[-1])
        checks.append(tmp_path / "results" / "verification" / f"{trace}_beta30_checks.nc")
        assert cli.main(["checks", "--geometry", str(directory), "--mesh", str(meshes[-1]),
                         "--run", str(runs[-3]), "--out", str(checks[-1])]) == 0
    # the trace level's files, constructed: the SBG's fronts better in the paper's cell, 3
    # matched pairs (too few for any matched cell to resolve)
    from tests.tables.test_trace_level import fronts_cell, matched

    trace_files = {"trace_fronts_files": [tmp_path / "results" / "optimise" / "trace_fronts.nc"],
                   "matched_pairs_files": [tmp_path / "results" / "optimise" / "matched_pairs.nc"]}
    write_dataset(fronts_cell(0.3, 0.0, seed=8), trace_files["trace_fronts_files"][0])
    write_dataset(matched(n=3), trace_files["matched_pairs_files"][0])
    out = tmp_path / "reports" / "paper.html"
    reports.render_report("paper", out, {"runs": runs, "mesh_files": meshes,
                                         "geometry_dirs": geometry, "paper_engine": "pybullet",
                                         "line_engine": "compiled", "checks_files": checks,
                                         "sensitivity_runs": sensitivity, **trace_files,
                                         **STATISTICS})
    html = out.read_text(encoding="utf-8")
    assert report_leaks(html) == []
    assert ("a pair modified from the paper's Table 1 (9:37 teeth, module 4.5 mm, spiral angle "
            "30°; face width 25 mm; changed: spiral angle 30°)") in html
    origins = re.findall(r'<td class="text">([^<]*)</td><td class="text">[^<]*</td>'
                         r'<td class="text">(paper Table 1|assumed|changed[^<]*)</td>', html)
    assert [(q, o) for q, o in origins if o.startswith("changed")] == [
        ("mean spiral angle βm", "changed (paper: 35)")]
    assert ("outer transverse module m", "paper Table 1") in origins
    # the first screen: the banner, then the matrix and its legend, before the finding
    assert (html.index("Coarse configuration") < html.index('class="lsbg-verdicts"')
            < html.index('class="lsbg-legend"') < html.index('class="lsbg-finding"'))
    assert "simulation.duration_s 0.05 (study: 1)" in html
    # the matrix's columns: as published and the trace (no practice or best pair here), each
    # trace cell with its count; under the matrix at most three sentences before the picture
    matrix = html[html.index('class="lsbg-verdicts"'):html.index("</table>",
                                                                 html.index('class="lsbg-verdicts"'))]
    headers = re.findall(r"<th>([^<]*)</th>", matrix)
    assert headers == ["the paper's claim", "as published",
                       "the trace (front against front, matched designs)"]
    cells = re.findall(r"<b>([^<]*)</b><br/?><small>([^<]*)</small>", matrix)
    # per claim: as published, the trace (stability 4 cells; contact: the fronts and the FE TE)
    assert cells[1::2] == [("not shown", "4 cells"), ("not shown", "3 cells"),
                           ("not shown", "3 cells")]
    below = html[html.index('class="lsbg-legend"'):html.index("The assembled pairs")]
    below = re.sub(r"<[^>]+>", " ", below[below.index("</div>"):])
    assert 1 <= len(re.findall(r"[.!?](?=\s|$)", below.strip())) <= 3, below
    assert "3 matched pairs of 30 sought" in below
    # the claims table's column and Section 20's cells of the trace level
    assert '<th>the trace</th>' in html or 'the trace</th>' in html
    assert "The trace level" in html and "FE root stress, pinion" in html


@pytest.fixture(scope="module")
def sweep_pages(study_files, tmp_path_factory):
    """The sweep report of the same inputs rendered in two directories, ``one`` and ``two``
    (each a copy of the inputs, named relative to it but for the summary, named by its
    absolute path inside it): ``{name: (directory, report)}``. One pair of renders serves
    the report's content and its independence of the directory."""
    pages = {}
    for name in ("one", "two"):
        root = tmp_path_factory.mktemp(f"sweep_{name}")
        copies = {}  # each input's copy, named relative to root
        for key in ("sweep", "summary", "speed_curve", "rating_sweep", "vh"):
            files = study_files[key] if key == "vh" else [study_files[key]]
            copies[key] = [f"results/{key}/{Path(f).name}" for f in files]
            for source, target in zip(files, copies[key]):
                (root / target).parent.mkdir(parents=True, exist_ok=True)
                shutil.copy2(source, root / target)
        parameters = {f"{key}_file": copies[key][0]
                      for key in ("sweep", "speed_curve", "rating_sweep")}
        parameters.update(summary_file=root / copies["summary"][0], vh_files=copies["vh"],
                          steady_state_after_s=0.01)
        out = root / "reports" / "sweep.html"
        reports.render_report("sweep", out, parameters, cwd=root)
        pages[name] = (root, out)
    return pages


def test_sweep_report(sweep_pages):
    _, out = sweep_pages["one"]
    html = check_html(out, ["Spiral-angle sweep", "1. Loaded tooth contact",
                            "2. Fluctuations against", "3. Which type",
                            "4. The dynamic-factor curve", "5. The design points",
                            "6. The contact state against spiral angle",
                            "7. The paper's three claims against spiral angle",
                            "8. Parameter sweeps", "9. The SBG's cutter radius", "10. Conclusion",
                            "Appendix A. The loaded TCA", "Appendix B. Inputs"],
                      # loaded TCA, fluctuations, ratios, speed curve, Campbell map, the
                      # contact state against spiral angle, ISO 10300 against spiral angle
                      images=7, code_snippets=["tables.sweep_fluctuation_table", "import xarray"])
    # the three claims per angle; the standard rates the two types alike at 35°
    assert "ISO 10300 contact stress LSBG/SBG" in html
    assert "ISO 10300 pinion root stress: lives longer" in html
    assert "the standard rates the LSBG and each SBG (SBG, paper's arc) alike at every angle" in html
    assert "This study has no parameter sweeps" in html
    assert "std(SBG)/std(LSBG)" in html and "static TE peak to peak [µrad]" in html
    assert "natural frequency [Hz]" in html and "3 speeds" in html
    # the point model's dynamic factors get their sentence; the full table is attached
    assert "Dynamic factors." in html
    attached = [t for t in embedded_csv(html).values()
                if {"dynamic_factor", "gear_speed_sampled_std"} <= set(t.columns)]
    assert len(attached) == 1 and len(attached[0]) == 4   # 2 types x 2 contact models


def test_sweep_report_with_both_sbgs_names_each_by_its_construction(study_files, tmp_path):
    """A sweep with ISO 23509's SBG beside the paper's arc (workflow/config-sweep-face-milled.yaml):
    every comparison sets the LSBG against each SBG, named by its construction."""
    from lsbg.gear.design import TRACE_NAMES

    root = tmp_path
    geometry = root / "results" / "geometry" / "face_milled_beta35"
    write_geometry(GearPairDesign(trace="face_milled"), geometry)
    runs = [study_files["runs"][(t, m, "compiled")] for t in ("logarithmic", "circular")
            for m in ("point", "line")]
    for model, params in (("point", ContactParameters()), ("line", ContactParameters(model="line"))):
        path = root / "results" / "runs" / f"face_milled_beta35_{model}_compiled.nc"
        write_dataset(simulate(geometry, SHORT.replace(engine="compiled"), params), path)
        runs.append(path)
    mesh = root / "results" / "mesh" / "face_milled_beta35.nc"
    write_dataset(ltca_for_geometry(geometry, 1964.99, phases=64), mesh)
    vh = root / "results" / "vh" / "face_milled_beta35.nc"
    assert cli.main(["misalignment-map", "--geometry", str(geometry),
                     "--set", "flank_modification.lengthwise_crowning_um=25",
                     "--set", "flank_modification.profile_crowning_um=5",
                     "--set", "misalignment_map.steps=3", "--set", "misalignment_map.positions=24",
                     "--set", "misalignment_map.load_torque_N_m=500", "--out", str(vh),
                     "--tca-out", str(root / "results" / "tca" / "face_milled_beta35.nc")]) == 0
    meshes = [*study_files["meshes"].values(), mesh]
    sweep = root / "results" / "sweep.nc"
    write_dataset(combine_runs(runs, meshes=meshes, vh_maps=[*study_files["vh"], vh]), sweep)
    summary = root / "results" / "summary.csv"
    summary_table(runs, steady_state_after=0.01, window=(0.01, 0.05), subgroup_size=5,
                  meshes=meshes).to_csv(summary, index=False)
    rating = root / "results" / "rating_sweep.nc"
    assert cli.main(["rate-sweep", "--summary", str(summary), "--out", str(rating)]) == 0
    out = root / "reports" / "sweep.html"
    reports.render_report("sweep", out, {"sweep_file": sweep, "summary_file": summary,
                                         "rating_sweep_file": rating, "steady_state_after_s": 0.01,
                                         "vh_files": [*study_files["vh"], vh]}, cwd=root)
    html = check_html(out, ["Spiral-angle sweep", "3. Which type", "7. The paper's three claims"],
                      images=5, code_snippets=["tables.sweep_fluctuation_table"])
    text = re.sub(r"<[^>]+>", " ", html).replace("&#x27;", "'").replace("&#39;", "'")
    arc, iso = TRACE_NAMES["circular"], TRACE_NAMES["face_milled"]
    for name in (arc, iso):
        assert f"LSBG against the {name}" in text          # the finding, per SBG
    # the ratio table and the claims table: one row per quantity (or angle) and SBG, named
    named = [t for t in re.findall(r"<table.*?</table>", html, re.S)
             if "ratio SBG/LSBG" in t or "contact state: pattern moves less" in t]
    assert len(named) == 2
    for table in named:
        cells = [c.replace("&#x27;", "'").replace("&#39;", "'")
                 for c in re.findall(r"<td[^>]*>(.*?)</td>", table)]
        assert cells.count(arc) == cells.count(iso) >= 1


def test_verification_report_via_cli_with_relative_paths(study_files, monkeypatch, capsys):
    root = study_files["root"]
    monkeypatch.chdir(root)
    relative = {key: path.relative_to(root) for key, path in study_files["runs"].items()}
    geometry = [study_files["geometry"][t].relative_to(root) for t in ("logarithmic", "circular")]
    convergence = [path.relative_to(root) for path in study_files["convergence"]]
    meshes = [path.relative_to(root) for path in study_files["meshes"].values()]
    checks = [path.relative_to(root) for path in study_files["checks"]]
    code = cli.main(["report", "verification", "--out", "reports/verification.html",
                     "--param", f"convergence_files=[{', '.join(map(str, convergence))}]",
                     f"geometry_dirs=[{', '.join(map(str, geometry))}]",
                     f"runs=[{', '.join(map(str, relative.values()))}]",
                     f"mesh_files=[{', '.join(map(str, meshes))}]",
                     f"checks_files=[{', '.join(map(str, checks))}]",
                     "--param", "steady_state_after_s=0.01"])
    assert code == 0, capsys.readouterr().err
    html = check_html(root / "reports" / "verification.html",
                      ["Verification", "1. Convergence", "2. The engines",
                       "3. Geometry checks", "3.1 Spiral angle", "3.2 Normal pressure angle",
                       "3.3 Conjugacy", "4. The loaded tooth contact analysis",
                       "5. The contact state", "Appendix. Inputs and settings"],
                      # convergence (two models), engine agreement, spiral angle, pressure
                      # angle, conjugacy
                      images=6, code_snippets=["verification_tables.conjugacy_table(ds)"])
    # the finding: how many checks pass, and the checks that must pass even on short runs
    assert re.search(r"<strong>(All )?\d+ of \d+ checks pass</strong>", html)
    for check in ("LSBG spiral angle constant along the face", "flanks conjugate",
                  "no transmission error without load", "loaded TCA linear in load",
                  "contact state: conjugate, aligned pair without transmission error",
                  "contact state: backlash from the coast flanks equals the design",
                  "crowned pair's transmission error against its closed-form parabola",
                  "line model on the separation field against the surface TCA",
                  "an offset E of ±0.1 mm moves the bearing pattern either way"):
        assert re.search(r'<td class="text">' + re.escape(check) + r'[^<]*</td>'
                         r'<td class="text">[^<]*</td><td class="text">PASS</td>', html), check
    # paths stay relative to the study's directory: the report does not name it
    assert "results/runs/" in html and str(root) not in html


def test_failing_notebook_raises_and_writes_nothing(study_files, tmp_path):
    out = tmp_path / "paper.html"
    (tmp_path / ".paper.html.k1ll3d.tmp").mkdir()    # left by a killed report job: removed
    parameters = {**paper_parameters(study_files), "mesh_files": [tmp_path / "missing.nc"]}
    with pytest.raises(reports.ReportError, match=r"paper.ipynb failed in cell .*"
                                                   r"FileNotFoundError: .*missing.nc"):
        reports.render_report("paper", out, parameters)
    assert list(tmp_path.iterdir()) == []


def test_a_failing_notebook_is_exit_2_naming_the_cell(study_files, tmp_path, capsys):
    parameters = {**paper_parameters(study_files), "mesh_files": [tmp_path / "missing.nc"]}
    argv = ["report", "paper", "--out", str(tmp_path / "p.html")]
    for key, value in parameters.items():
        text = (f"[{', '.join(str(v) for v in value)}]" if isinstance(value, list)
                else str(value))
        argv += ["--param", f"{key}={text}"]
    assert cli.main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("lsbg report: error: report 'paper': notebook paper.ipynb failed in "
                          "cell ") and "missing.nc" in err, err
    assert err.count("\n") == 1 and not (tmp_path / "p.html").exists()


def test_bad_report_input_exit_2(tmp_path, capsys):
    out = tmp_path / "x.html"
    assert cli.main(["report", "nosuch", "--out", str(out)]) == 2
    assert "available: paper, sweep, verification" in capsys.readouterr().err
    assert cli.main(["report", "sweep", "--out", str(out), "--param", "sweep_fle=a.nc"]) == 2
    assert "sweep_fle" in capsys.readouterr().err
    assert cli.main(["report", "sweep", "--out", str(out), "--param", "no-equals"]) == 2
    assert not out.exists()


def test_notebooks_declare_the_interface_parameters():
    expected = {
        "paper": {"runs", "sensitivity_runs", "mesh_files", "geometry_dirs", "paper_engine",
                  "line_engine", "steady_state_after_s", "chart_window_start_s",
                  "chart_window_stop_s", "subgroup_size", "sweep_file", "tca_files", "vh_files",
                  "fe_ltca_files", "rating_files", "vh_case_files", "fe_case_files",
                  "checks_files", "parameter_sweep_files", "practice_run_files",
                  "practice_vh_files", "practice_rating_files", "practice_fe_ltca_files",
                  "practice_geometry_dirs", "load_curve_files", "load_spectrum_fractions",
                  "load_spectrum_shares", "practice_profile_shift", "practice_addendum_rule",
                  "optimise_front_files", "optimise_release_files", "trace_fronts_files",
                  "matched_pairs_files", "best_run_files",
                  "best_vh_files", "best_rating_files", "best_fe_ltca_files",
                  "practice_sensitivity_runs", "practice_vh_case_files",
                  "practice_fe_case_files", "best_sensitivity_runs", "best_vh_case_files",
                  "best_fe_case_files"},
        "sweep": {"sweep_file", "summary_file", "speed_curve_file", "steady_state_after_s",
                  "vh_files", "rating_sweep_file", "parameter_sweep_files", "cutter_files"},
        "verification": {"convergence_files", "geometry_dirs", "runs", "mesh_files",
                         "steady_state_after_s", "checks_files"},
    }
    import nbformat

    for name, parameters in expected.items():
        path = reports.notebook_path(name)
        assert set(reports.notebook_parameters(path)) == parameters
        nb = nbformat.read(path, as_version=4)
        assert nb.metadata["language_info"]["name"] == "python"
        assert nb.metadata["kernelspec"]["name"] == "python3"
        assert all(not cell.get("outputs") for cell in nb.cells if cell.cell_type == "code")


def test_parse_and_resolve_parameters(tmp_path):
    assert reports.parse_parameter("runs=[a.nc, b.nc]") == ("runs", ["a.nc", "b.nc"])
    assert reports.parse_parameter("steady_state_after_s=0.2") == ("steady_state_after_s", 0.2)
    assert reports.parse_parameter("sbg_reference_run=") == ("sbg_reference_run", "")
    assert reports.parse_parameter("x=a=b") == ("x", "a=b")
    for bad in ("novalue", "=3", "a b=1", "x=[unclosed"):
        with pytest.raises(ValueError, match="--param"):
            reports.parse_parameter(bad)
    resolved = reports.resolve_parameters(
        {"runs": ["a.nc", "/abs/b.nc", str(tmp_path / "results" / "c.nc")], "sbg_run": "",
         "lsbg_geometry": "results/../g", "summary_file": "../s.csv", "subgroup_size": 4,
         "title": "keep/me"}, cwd=tmp_path)
    # inside the working directory: relative (reports do not depend on where the study ran)
    assert resolved == {"runs": ["a.nc", "/abs/b.nc", "results/c.nc"], "sbg_run": "",
                        "lsbg_geometry": "g", "summary_file": (tmp_path.parent / "s.csv").as_posix(),
                        "subgroup_size": 4, "title": "keep/me"}


def test_report_is_the_same_in_another_directory(sweep_pages):
    """The same inputs in two directories give the same HTML, apart from the time stamp."""
    pages = []
    for root, out in sweep_pages.values():
        html = out.read_text(encoding="utf-8")
        assert str(root) not in html and str(root.parent) not in html
        assert "results/" in html          # the inputs are named, relative
        pages.append(re.sub(r"computed with lsbg \S+ on [0-9-]+ [0-9:]+ UTC", "", html))
    assert pages[0] == pages[1]
