"""``lsbg check-config``: the workflow's check outside Snakemake, naming a YAML error's line."""

import yaml

from lsbg import cli
from lsbg.cli.config import REPO, merge_config


def test_merge_config_merges_mappings_and_replaces_values():
    base = {"design": {"module_mm": 4.5, "gear_teeth": 37}, "sweep": {"traces": ["a", "b"]}}
    merged = merge_config(base, {"design": {"module_mm": 5}, "sweep": {"traces": ["a"]}})
    assert merged == {"design": {"module_mm": 5, "gear_teeth": 37}, "sweep": {"traces": ["a"]}}
    assert base["design"]["module_mm"] == 4.5          # the base is not changed


def test_yaml_error_names_the_file_line_and_column(tmp_path, capsys):
    bad = tmp_path / "bad.yaml"
    bad.write_text("design:\n  module_mm: 4.5\n  gear_teeth: [37\n")
    assert cli.main(["check-config", str(bad)]) == 2
    err = capsys.readouterr().err
    assert str(bad) in err and "line 4, column 1" in err and "Traceback" not in err


def test_invalid_value_is_named_by_its_key_and_valid_configs_pass(tmp_path, capsys):
    bad = tmp_path / "wide.yaml"
    bad.write_text(yaml.safe_dump({"design": {"face_width_mm": 500}}))
    assert cli.main(["check-config", str(bad)]) == 2
    assert "design.face_width_mm = 500" in capsys.readouterr().err
    test_config = REPO / "workflow" / "config-test.yaml"
    assert cli.main(["check-config", str(test_config)]) == 0
    assert "valid: 2 design points" in capsys.readouterr().out


def test_a_commands_config_reads_the_files_check_config_reads(tmp_path, capsys):
    """``lsbg <command> --config FILE`` reads a study configuration as check-config does:
    the workflow's files are accepted, merged in order; a YAML error names the file, line
    and column in one line, exit code 2, before any work."""
    from lsbg.cli.options import settings_of

    files = [REPO / "workflow" / "config.yaml", REPO / "workflow" / "config-test.yaml"]
    args = cli.build_parser().parse_args(
        ["summary", "--runs", "r.nc", "--out", str(tmp_path / "s.csv"),
         *[w for path in files for w in ("--config", str(path))]])
    settings = settings_of(args)
    expected = merge_config(*[yaml.safe_load(path.read_text()) for path in files])
    assert settings["statistics"] == {**settings["statistics"], **expected["statistics"]}
    assert settings["sweep"] == expected["sweep"]
    bad = tmp_path / "bad.yaml"
    bad.write_text("statistics:\n  subgroup_size: 4\n  control_chart_window_s: [0.8\n")
    assert cli.main(["summary", "--runs", "r.nc", "--config", str(bad),
                     "--out", str(tmp_path / "s.csv")]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"lsbg summary: error: --config {bad}: not valid YAML (line 4, "
                          f"column 1") and err.count("\n") == 1, err
    assert not (tmp_path / "s.csv").exists()


def test_a_broken_or_missing_file_is_one_line_from_a_real_process(tmp_path):
    """The README's first command for a study of one's own: the file, line and column of
    a YAML error, or the missing file, in one line (exit 2), no traceback."""
    import subprocess
    import sys

    bad = tmp_path / "bad.yaml"
    bad.write_text("design:\n  face_width_mm: [25\nsweep: {}\n")
    for path, where in ((bad, "not valid YAML (line 3, column 6"),
                        (tmp_path / "missing.yaml", "No such file")):
        done = subprocess.run([sys.executable, "-c", "import sys; from lsbg.cli import main; "
                               "sys.exit(main())", "check-config", str(path)],
                              capture_output=True, text=True, timeout=120)
        assert done.returncode == 2, done.stderr
        assert done.stderr.count("\n") == 1 and str(path) in done.stderr, done.stderr
        assert where in done.stderr and "Traceback" not in done.stderr + done.stdout


def test_the_study_files_set_the_spiral_angle_once(tmp_path, capsys):
    at30 = tmp_path / "at30.yaml"
    at30.write_text("design:\n  spiral_angle_deg: 30\n")
    assert cli.main(["check-config", str(REPO / "workflow" / "config-test.yaml"),
                     str(at30)]) == 0
    assert "valid: 2 design points" in capsys.readouterr().out
    twice = tmp_path / "twice.yaml"
    twice.write_text("paper_spiral_angle_deg: 30\n")
    assert cli.main(["check-config", str(REPO / "workflow" / "config-test.yaml"),
                     str(twice)]) == 2
    assert ("design.spiral_angle_deg = 35: the study's design point, and "
            "paper_spiral_angle_deg = 30 another" in capsys.readouterr().err)
