"""No traceback for a user's mistake: every bad input of the command line gives one line
on stderr that names the file, and exit code 2, before any work starts."""

import json
import os
import shutil
import subprocess
import sys

import numpy as np
import pytest
import xarray as xr

from lsbg import cli
from lsbg.gear.design import GearPairDesign
from lsbg.solid.export import write_geometry
from lsbg.files import write_dataset


@pytest.fixture(scope="module")
def world(tmp_path_factory):
    """Good and bad inputs side by side: name -> path."""
    root = tmp_path_factory.mktemp("cli_errors")
    geo = root / "logarithmic_beta35"
    write_geometry(GearPairDesign(), geo)
    w = {"root": root, "geo": geo}
    for name in ("edited", "no_urdf", "bad_manifest"):
        w[name] = shutil.copytree(geo, root / name)
    record = json.loads((w["edited"] / "design.json").read_text(encoding="utf-8"))
    record["spiral_angle_deg"] = 40.0                       # 35 deg meshes labelled 40
    (w["edited"] / "design.json").write_text(json.dumps(record, indent=1), encoding="utf-8")
    (w["no_urdf"] / "pair.urdf").unlink()
    (w["bad_manifest"] / "manifest.json").write_text("{", encoding="utf-8")
    w["renamed"] = shutil.copytree(geo, root / "logarithmic_beta40")
    w["empty"] = root / "empty"
    w["empty"].mkdir()
    w["file"] = root / "plain.txt"
    w["file"].write_text("not a directory")
    w["missing"] = root / "missing"
    w["missing_nc"] = root / "missing.nc"
    w["truncated"] = root / "truncated.nc"
    w["truncated"].write_bytes((geo / "flanks.nc").read_bytes()[:5000])
    w["text"] = root / "text.nc"
    w["text"].write_text("hello")
    w["not_a_run"] = root / "not_a_run.nc"
    write_dataset(xr.Dataset({"x": ("t", np.arange(5.0), {"units": "1", "long_name": "x"})}),
                  w["not_a_run"])
    w["garbage_yaml"] = root / "garbage.yaml"
    w["garbage_yaml"].write_text("design: [unclosed\n")
    w["duplicated"] = root / "duplicated.yaml"
    w["duplicated"].write_text("contact:\n  slices: 10\n  slices: 30\n")
    w["bare_design"] = root / "bare_design.yaml"            # the former --design FILE
    w["bare_design"].write_text("module_mm: 5\nspiral_angle_deg: 30\n")
    w["out"] = root / "out.nc"                              # never written by a bad command
    return w


# name -> (command line, fields {name} are paths of `world`; the path the message names)
TABLE = {
    # --geometry: missing, a file, empty, edited, renamed, incomplete, corrupt manifest
    "simulate missing geometry": ("simulate --geometry {missing} --out {out}", "missing"),
    "simulate file as geometry": ("simulate --geometry {file} --out {out}", "file"),
    "simulate empty geometry": ("simulate --geometry {empty} --out {out}", "empty"),
    "simulate edited design.json": ("simulate --geometry {edited} --engine compiled "
                                    "--out {out}", "edited"),
    "simulate renamed directory": ("simulate --geometry {renamed} --out {out}", "renamed"),
    "convergence missing geometry": ("convergence --geometry {missing} --out {root}/c.csv",
                                     "missing"),
    "convergence without URDF": ("convergence --geometry {no_urdf} --out {root}/c.csv",
                                 "no_urdf"),
    "ltca edited design.json": ("ltca --geometry {edited} --out {out}", "edited"),
    "ltca empty geometry": ("ltca --geometry {empty} --out {out}", "empty"),
    "mesh-mode corrupt manifest": ("mesh-mode --geometry {bad_manifest}", "bad_manifest"),
    "speed-run file as geometry": ("speed-run --geometry {file} "
                                   "--set simulation.pinion_speed_deg_s=2000 --out {out}", "file"),
    "sensitivity missing geometry": ("sensitivity --geometry {missing} --case slices=2 "
                                     "--out {root}/s_{{case}}.nc", "missing"),
    # run files: missing, truncated, not NetCDF, a directory, not a run
    "combine missing run": ("combine --runs {missing_nc} --out {out}", "missing_nc"),
    "combine truncated run": ("combine --runs {truncated} --out {out}", "truncated"),
    "combine text file": ("combine --runs {text} --out {out}", "text"),
    "combine directory as run": ("combine --runs {empty} --out {out}", "empty"),
    "combine not a run": ("combine --runs {not_a_run} --out {out}", "not_a_run"),
    "summary truncated run": ("summary --runs {truncated} --out {root}/s.csv", "truncated"),
    "speed-curve truncated run": ("speed-curve --runs {truncated} --out {out}", "truncated"),
    "convergence truncated known run": ("convergence --geometry {geo} --known {truncated} "
                                        "--out {root}/c.csv", "truncated"),
    # configuration files (the design's too: a file with a design section)
    "simulate missing config": ("simulate --geometry {geo} --config {missing} --out {out}",
                                "missing"),
    "geometry garbage config file": ("geometry --config {garbage_yaml} --out {root}/g",
                                     "garbage_yaml"),
    "geometry missing config": ("geometry --config {missing} --out {root}/g", "missing"),
    # outputs, checked before the work: a directory for a file, below a file
    "simulate out is a directory": ("simulate --geometry {geo} --out {empty}", "empty"),
    "simulate out below a file": ("simulate --geometry {geo} --out {file}/run.nc", "file"),
    "geometry out is a file": ("geometry --out {file}", "file"),
    "points out below a file": ("points --spiral-angles 30 35 "
                                "--geometry-out {file}/beta{{spiral}}", "file"),
    "ltca out below a file": ("ltca --geometry {geo} --out {file}/mesh.nc", "file"),
    "convergence out below a file": ("convergence --geometry {geo} --out {file}/c.csv", "file"),
    "sensitivity out below a file": ("sensitivity --geometry {geo} --case slices=2 "
                                     "--out {file}/s_{{case}}.nc", "file"),
    "speed-run out is a directory": ("speed-run --geometry {geo} "
                                     "--set simulation.pinion_speed_deg_s=2000 --out {empty}",
                                     "empty"),
    "combine out below a file": ("combine --runs {missing_nc} --out {file}/sweep.nc", "file"),
    "summary out is a directory": ("summary --runs {truncated} --out {empty}", "empty"),
    "speed-curve out below a file": ("speed-curve --runs {truncated} --out {file}/curve.nc",
                                     "file"),
    "report out below a file": ("report paper --out {file}/p.html", "file"),
}


@pytest.fixture
def no_work(monkeypatch):
    """Any integration, geometry, loaded TCA or convergence study started by a bad command
    fails the test: the bad input must be caught before the work starts."""
    def started(*args, **kwargs):
        raise AssertionError("the work started before the bad input was found")

    # a module that binds one of these by name at import (lsbg.tca.vh_map: loaded_tca)
    # is imported before the patch, or it would keep the stand-in after this test
    import lsbg.tca.vh_map  # noqa: F401

    for target in ("lsbg.dynamics.model.MeshingModel.run", "lsbg.solid.export.write_geometry",
                   "lsbg.tca.loaded.loaded_tca", "lsbg.experiments.verification.convergence_study"):
        monkeypatch.setattr(target, started)


def one_line_exit_2(world, line, capsys):
    """Run ``line`` (formatted with the world's paths): exit code 2, one line on stderr
    naming the command, no traceback, nothing written; the line."""
    argv = [word.format(**world) for word in line.split()]
    before = sorted(world["root"].rglob("*"))
    assert cli.main(argv) == 2
    out, err = capsys.readouterr()
    assert "Traceback" not in out + err
    assert err.startswith(f"lsbg {argv[0]}: error: ") and err.count("\n") == 1, err
    assert sorted(world["root"].rglob("*")) == before         # nothing written
    return err


@pytest.mark.parametrize("case", TABLE)
def test_bad_input_is_one_line_naming_the_file_exit_2(world, case, capsys, no_work):
    line, named = TABLE[case]
    assert world[named].name in one_line_exit_2(world, line, capsys)


def test_edited_design_json_says_how_to_regenerate(world, capsys):
    assert cli.main(["simulate", "--geometry", str(world["edited"]), "--out",
                     str(world["out"])]) == 2
    err = capsys.readouterr().err
    assert f"{world['edited'] / 'design.json'}: changed since 'lsbg geometry' wrote it" in err
    assert f"delete {world['edited']} and rerun snakemake" in err


def test_unwritable_out_folder(world, capsys, no_work, tmp_path):
    """A folder whose mode forbids writing; as root (who passes any mode, as on CI) a
    folder that takes no new entries whatever its mode, /proc: the probe file says so."""
    if os.geteuid() == 0:
        assert cli.main(["simulate", "--geometry", str(world["geo"]),
                         "--out", "/proc/run.nc"]) == 2
        assert "--out /proc/run.nc: cannot create files in /proc" in capsys.readouterr().err
        return
    locked = tmp_path / "locked"
    locked.mkdir()
    locked.chmod(0o500)
    try:
        assert cli.main(["simulate", "--geometry", str(world["geo"]),
                         "--out", str(locked / "run.nc")]) == 2
    finally:
        locked.chmod(0o700)
    assert f"cannot write in {locked}" in capsys.readouterr().err


def test_real_process_prints_no_traceback(world):
    """The installed entry point, in its own process: exit status 2, one line on stderr."""
    done = subprocess.run(
        [sys.executable, "-c", "import sys; from lsbg.cli import main; sys.exit(main())",
         "convergence", "--geometry", str(world["file"]), "--out", str(world["root"] / "c.csv")],
        capture_output=True, text=True, timeout=120)
    assert done.returncode == 2
    assert done.stderr == (f"lsbg convergence: error: {world['file']}: a file, not a geometry "
                           f"directory (written by 'lsbg geometry')\n")
    assert "Traceback" not in done.stdout


#: Sensitivity cases given to a command that cannot take them, or badly: one line, exit
#: 2, before any work, nothing written.
CASE_ERRORS = {
    "ltca case of another stage": (
        "ltca --geometry {geo} --case mesh_damping_ratio=2 --case-out {root}/c_{{case}}.nc "
        "--out {out}", "--case 'mesh_damping_ratio=2': a mesh_damping_ratio case does not "
                       "change this analysis"),
    "ltca case without a template": (
        "ltca --geometry {geo} --case crowning=2 --out {out}",
        "--case: needs --case-out, a file template with {{case}}"),
    "sensitivity negative crowning": (
        "sensitivity --geometry {geo} --case crowning=-1 --out {root}/s_{{case}}.nc",
        "sensitivity.crowning factor -1: must be a number >= 0"),
    "sensitivity unknown envelope": (
        "sensitivity --geometry {geo} --case displacement=corners --out {root}/s_{{case}}.nc",
        "sensitivity.displacement value 'corners'"),
    "sensitivity cases on one file": (
        "sensitivity --geometry {geo} --case crowning=0.5 --case crowning=2 --out {root}/s.nc",
        "the cases would write the same file"),
    "misalignment-map even case steps": (
        "misalignment-map --geometry {geo} --case crowning=2 "
        "--set misalignment_map.sweep_steps=4 --case-out {root}/v_{{case}}.nc "
        "--out {root}/vh.nc", "= 4: must be an odd whole number >= 3"),
    "a bare mapping of design keys": (
        "geometry --config {bare_design} --out {root}/g",
        "module_mm: unknown key (known: contact, cutter_sweep, design,"),
    "a configuration file with a key twice": (
        "simulate --geometry {geo} --config {duplicated} --out {out}",
        "line 3: key 'contact.slices' again (first at line 2)"),
    "rate case run without a name": (
        "rate --geometry {geo} --case-run {out} --out {root}/r.nc",
        "--case-run '{out}': must be NAME=VALUE"),
}


@pytest.mark.parametrize("case", CASE_ERRORS)
def test_bad_sensitivity_cases_are_one_line_exit_2(world, case, capsys, no_work):
    line, message = CASE_ERRORS[case]
    err = one_line_exit_2(world, line, capsys)
    assert message.format(**world) in err, err


def test_even_case_steps_name_the_sweep_steps_key(world, capsys, no_work):
    """The cases' maps take misalignment_map.sweep_steps (the former --case-steps): its
    bad value is named by its own key."""
    err = one_line_exit_2(world, "misalignment-map --geometry {geo} --case crowning=2 "
                                 "--set misalignment_map.sweep_steps=4 "
                                 "--case-out {root}/v_{{case}}.nc --out {root}/vh.nc", capsys)
    assert "misalignment_map.sweep_steps = 4" in err, err


@pytest.mark.parametrize("line", [
    "simulate --geometry {geo} --out /proc/nope/run.nc",
    "ltca --geometry {geo} --out /proc/nope/mesh.nc",
    "geometry --out /proc/nope/geo",
    "combine --runs {truncated} --out /proc/nope/sweep.nc",
    "report paper --out /proc/nope/p.html",
    "rate --geometry {geo} --out /proc/nope/r.nc",
])
def test_an_output_folder_that_cannot_be_created_is_one_line(world, line, capsys, no_work):
    """/proc takes no new entries even for root, whom os.access lets write anywhere: the
    command says so before its work, instead of a traceback from mkdir at its end."""
    err = one_line_exit_2(world, line, capsys)
    assert "/proc/nope" in err and "cannot create files in /proc" in err, err
