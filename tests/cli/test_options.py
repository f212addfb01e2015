"""One override grammar (issue 35): every command that reads the study's configuration takes
``--config FILE`` and ``--set section.key=value``, typed and checked by the schema before any
work; a bad key or value is one line naming it, exit code 2, nothing written; the former
per-key options are refused by argparse."""

import pytest
import yaml

from lsbg import cli
from lsbg.cli import build_parser
from lsbg.cli.options import settings_of
from lsbg.gear.design import GearPairDesign
from lsbg.solid.export import write_geometry


@pytest.fixture(scope="module")
def world(tmp_path_factory):
    root = tmp_path_factory.mktemp("cli_settings")
    geo = root / "logarithmic_beta35"
    write_geometry(GearPairDesign(), geo)
    text = root / "plain.txt"
    text.write_text("not a run")
    return {"root": root, "geo": geo, "text": text, "out": root / "out.nc"}


#: The smallest command line of each command that reads the configuration (fields: `world`).
COMMANDS = {
    "geometry": "--out {root}/g",
    "points": "--geometry-out {root}/g{{spiral}}",
    "simulate": "--geometry {geo} --out {out}",
    "sensitivity": "--geometry {geo} --case slices=2 --out {root}/s_{{case}}.nc",
    "convergence": "--geometry {geo} --out {root}/c.csv",
    "ltca": "--geometry {geo} --out {out}",
    "compliance": "--geometry {geo} --out {out}",
    "rate": "--geometry {geo} --out {out}",
    "tca": "--geometry {geo} --out {out}",
    "misalignment-map": "--geometry {geo} --out {out}",
    "mesh-mode": "--geometry {geo} --out {root}/m.csv",
    "speed-run": "--geometry {geo} --out {out}",
    "sweep-run": "--geometry {geo} --sweep s --point {out} contact.slices=4",
    "sweep-combine": "--runs {text} --out {out}",
    "summary": "--runs {text} --out {root}/s.csv",
    "rate-sweep": "--summary {text} --out {out}",
    "practice": "--out {root}/practice.yaml",
    "load-curve": "--geometry {geo} --compliance-file {root}/c.nc --out {out}",
    "optimise": "--geometry {geo} --out {out}",
    "release": "--geometry {geo} --front {text} --compliance-file {root}/c.nc --out {out} "
               "--overlay-out {root}/best.yaml",
    "converge-front": "--geometry {geo} --front {text} --release {root}/r.nc --out {out}",
    "cutter-point": "--roles nominal --radius-mm 76.2 --out {out}",
    "kernels": "--out {root}/kernels.json",
    "matched-pairs": "--converged {text} {text} --geometry {geo} {geo} --release {text} {text} "
                     "--compliance-file {root}/c.nc {root}/c.nc --rating {text} {text} "
                     "--front {text} --trace-fronts {text} --out {out}",
}

#: Commands that read files only (no configuration, no --set) and a command line of each.
FILES_ONLY = {"check-config": "config.yaml", "combine": "--runs r.nc --out o.nc",
              "speed-curve": "--runs r.nc --out o.nc", "report": "paper --out o.html",
              "checks": "--geometry g --mesh m.nc --run r.nc --out o.nc",
              "notebook-kernel": "--connection-file kernel.json",
              "trace-fronts": "--converged a.nc b.nc --out o.nc"}

#: A valid value other than the default of one key per section, and the value it reads as.
GOOD = {
    # (a value as YAML reads it, as it would stand in a config file: 30 is an int)
    "design": ("spiral_angle_deg", "30", 30),
    "simulation": ("time_step_s", "2e-6", 2e-6),
    "driveline": ("tyre_radius_m", "0.36", 0.36),
    "contact": ("model", "line", "line"),
    "flank_modification": ("lengthwise_crowning_um", "25.5", 25.5),
    "misalignment": ("pinion_axial_P_mm", "0.05", 0.05),
    "tca": ("positions", "40", 40),
    "tooth": ("ltca_positions", "48", 48),
    "misalignment_map": ("axes", "[P, G]", ["P", "G"]),
    "statistics": ("control_chart_window_s", "[0.01, 0.05]", [0.01, 0.05]),
    "rating": ("application_factor", "1.25", 1.25),
    "practice": ("load_range_phases", "64", 64),
    "optimise": ("seed", "3", 3),
    "limits": ("optimise_minutes", "20", 20),
    "speed_sweep": ("pinion_speeds_deg_s", "{start: 1000, stop: 8000, count: 4}",
                    {"start": 1000, "stop": 8000, "count": 4}),
}


def argv_of(world, command, *extra):
    return [command, *[w.format(**world) for w in COMMANDS[command].split()], *extra]


def subcommands():
    parser = build_parser()
    return next(a for a in parser._actions if a.__class__.__name__ == "_SubParsersAction").choices


@pytest.fixture
def no_work(monkeypatch):
    """Any stage started by a bad command fails the test."""
    def started(*args, **kwargs):
        raise AssertionError("the work started before the bad setting was found")

    import lsbg.tca.vh_map  # noqa: F401  (binds loaded_tca at import: imported before the patch)

    for target in ("lsbg.dynamics.model.MeshingModel.run", "lsbg.solid.export.write_geometry",
                   "lsbg.tca.loaded.loaded_tca", "lsbg.experiments.verification.convergence_study",
                   "lsbg.tooth.config.compliance_for_design", "lsbg.dynamics.load_model",
                   "lsbg.tca.analysis.tooth_contact_analysis", "lsbg.aggregate.summary.summary_table",
                   "lsbg.aggregate.sweep_dataset.sweep_rows",
                   "lsbg.experiments.rating_sweep.rating_by_angle"):
        monkeypatch.setattr(target, started)


def one_line_exit_2(world, argv, capsys):
    """``argv``: exit code 2, one line on stderr naming the command, nothing written."""
    before = sorted(world["root"].rglob("*"))
    assert cli.main([str(a) for a in argv]) == 2
    out, err = capsys.readouterr()
    assert "Traceback" not in out + err
    assert err.startswith(f"lsbg {argv[0]}: error: ") and err.count("\n") == 1, err
    assert sorted(world["root"].rglob("*")) == before
    return err


def test_every_command_that_reads_the_configuration_takes_config_and_set():
    """The table above is every command with --set; the others read no configuration."""
    with_set = set()
    for name, parser in subcommands().items():
        options = {o for action in parser._actions for o in action.option_strings}
        if "--set" in options:
            with_set.add(name)
            assert "--config" in options, name
            assert parser.get_default("sections"), name
        else:
            assert parser.get_default("sections") is None, name
    assert with_set == set(COMMANDS)
    assert set(subcommands()) == set(COMMANDS) | set(FILES_ONLY)


@pytest.mark.parametrize("command", sorted(FILES_ONLY))
def test_a_command_that_reads_files_only_refuses_set(command, capsys):
    build_parser().parse_args([command, *FILES_ONLY[command].split()])
    with pytest.raises(SystemExit) as exit_:
        build_parser().parse_args([command, *FILES_ONLY[command].split(), "--set",
                                   "contact.model=line"])
    assert exit_.value.code == 2
    assert "unrecognized arguments: --set contact.model=line" in capsys.readouterr().err


@pytest.mark.parametrize("command", COMMANDS)
def test_every_command_takes_set_for_each_of_its_sections(world, command):
    parser = build_parser()
    sections = subcommands()[command].get_default("sections")
    overrides = [f"{s}.{GOOD[s][0]}={GOOD[s][1]}" for s in sections]
    args = parser.parse_args(argv_of(world, command, *[w for o in overrides
                                                        for w in ("--set", o)]))
    settings = settings_of(args)
    for section in sections:
        key, _, value = GOOD[section]
        assert settings[section][key] == value, (section, key)
        assert type(settings[section][key]) is type(value), (section, key)
    # the schema's defaults fill in every other key of the sections
    assert settings["simulation"]["load_torque_N_m"] == 1964.99


def test_config_files_merge_in_order_and_set_comes_last(world, tmp_path):
    first, second = tmp_path / "first.yaml", tmp_path / "second.yaml"
    first.write_text(yaml.safe_dump({"contact": {"slices": 10, "model": "line"}}))
    second.write_text(yaml.safe_dump({"contact": {"slices": 30}}))
    parser = build_parser()
    files = ["--config", str(first), "--config", str(second)]
    settings = settings_of(parser.parse_args(argv_of(world, "simulate", *files)))
    assert settings["contact"]["slices"] == 30 and settings["contact"]["model"] == "line"
    settings = settings_of(parser.parse_args(argv_of(world, "simulate", *files, "--set",
                                                     "contact.slices=40", "--set",
                                                     "contact.slices=50")))
    assert settings["contact"]["slices"] == 50 and settings["contact"]["model"] == "line"


@pytest.mark.parametrize("command", COMMANDS)
def test_a_bad_key_is_one_line_naming_it_before_any_output(world, command, capsys, no_work):
    section = subcommands()[command].get_default("sections")[0]
    err = one_line_exit_2(world, argv_of(world, command, "--set", f"{section}.no_such_key=1"),
                          capsys)
    assert (f"--set '{section}.no_such_key=1': {section}.no_such_key: unknown key "
            f"(known: ") in err, err
    err = one_line_exit_2(world, argv_of(world, command, "--set", "nosuch.key=1"), capsys)
    assert "--set 'nosuch.key=1': nosuch: unknown key (known: " in err, err


@pytest.mark.parametrize("command", COMMANDS)
def test_a_bad_value_is_one_line_naming_it_before_any_output(world, command, capsys, no_work):
    section = subcommands()[command].get_default("sections")[-1]
    key = GOOD[section][0]
    err = one_line_exit_2(world, argv_of(world, command, "--set", f"{section}.{key}=abc"),
                          capsys)
    assert f"{section}.{key}: 'abc' is not" in err, err


@pytest.mark.parametrize("text, message", [
    ("simulation.duration_s=-1", "simulation.duration_s: -1 is less than or equal to the "
                                 "minimum of 0"),
    ("simulation.samples=2.5", "simulation.samples: 2.5 is not of type 'integer'"),
    ("contact.model=plane", "contact.model: 'plane' is not one of"),
    ("simulation.duration_s=.nan", "simulation.duration_s = nan: must be a finite number"),
    ("simulation.duration_s", "--set 'simulation.duration_s': must be section.key=value"),
    ("duration_s=1", "--set 'duration_s=1': duration_s: unknown key"),
])
def test_bad_values_are_named_with_the_value(world, text, message, capsys, no_work):
    err = one_line_exit_2(world, argv_of(world, "simulate", "--set", text), capsys)
    assert message in err, err


def test_a_number_is_a_number_as_the_schema_types_it(world, tmp_path, capsys):
    """``--set simulation.time_step_s=1e-6`` is a number (YAML 1.1 alone reads 1e-6 as
    text); a run takes it."""
    parser = build_parser()
    settings = settings_of(parser.parse_args(argv_of(world, "simulate", "--set",
                                                     "simulation.time_step_s=1e-6")))
    assert settings["simulation"]["time_step_s"] == 1e-6
    assert isinstance(settings["simulation"]["time_step_s"], float)
    # an integer given to a number key is a number; a number key of a whole value too
    settings = settings_of(parser.parse_args(argv_of(world, "simulate", "--set",
                                                     "simulation.duration_s=1")))
    assert settings["simulation"]["duration_s"] == 1.0
    # in a configuration file the same text is refused with a hint
    config = tmp_path / "dt.yaml"
    config.write_text("simulation:\n  time_step_s: 1e-6\n")
    err = one_line_exit_2(world, argv_of(world, "simulate", "--config", config), capsys)
    assert "simulation.time_step_s: '1e-6' is not of type 'number'" in err
    assert "write the mantissa with a decimal point" in err
    # a real run at a time step of 2e-6 s set that way
    out = tmp_path / "run.nc"
    assert cli.main(argv_of(world, "simulate")[:3] + [
        "--set", "simulation.time_step_s=2e-6", "--set", "simulation.duration_s=0.02",
        "--set", "simulation.samples=10", "--set", "simulation.ramp_time_s=0.01",
        "--set", "simulation.full_rate_after_s=0.01", "--out", str(out)]) == 0
    assert capsys.readouterr().out.startswith("lsbg simulate: pybullet engine, point model -> ")
    import xarray as xr

    with xr.open_dataset(out) as ds:
        assert ds.attrs["solver_time_step_s"] == 2e-6
        assert ds.attrs["solver_engine"] == "pybullet"
        assert ds.sizes["time"] == 11


#: The former per-key options (issue 35) and the commands that had them.
OLD = [
    ("geometry", ["--module-mm", "5"]), ("geometry", ["--spiral-angle", "30"]),
    ("geometry", ["--trace", "circular"]), ("geometry", ["--face-width-mm", "24"]),
    ("geometry", ["--design", "d.yaml"]), ("geometry", ["--modification", "bias_um=1"]),
    ("simulate", ["--set-contact", "slices=10"]), ("compliance", ["--set-tooth", "face_points=5"]),
    ("rate", ["--set-rating", "application_factor=1.25"]),
    ("tca", ["--modification", "bias_um=1"]), ("tca", ["--misalignment", "P=0.05"]),
    ("simulate", ["--contact-model", "line"]), ("simulate", ["--compliance", "fe"]),
    ("simulate", ["--duration", "0.05"]), ("simulate", ["--samples", "25"]),
    ("simulate", ["--dt", "1e-6"]), ("simulate", ["--rtol", "1e-8"]),
    ("simulate", ["--method", "LSODA"]), ("simulate", ["--pinion-speed", "2000"]),
    ("simulate", ["--ramp-time", "0.01"]), ("simulate", ["--load-torque", "100"]),
    ("simulate", ["--full-rate", "5000"]), ("simulate", ["--full-rate-after", "0.01"]),
    ("ltca", ["--phases", "16"]), ("ltca", ["--load-torque", "100"]),
    # (not a prefix of another option: --compliance-file, --compliance-out)
    ("ltca", ["--compliance", "fe"]), ("points", ["--compliance", "fe"]),
    ("points", ["--trace", "circular"]),
    ("tca", ["--positions", "24"]), ("tca", ["--marking-um", "6"]),
    ("misalignment-map", ["--axes", "P", "G"]), ("misalignment-map", ["--range", "0.05"]),
    ("misalignment-map", ["--steps", "3"]), ("misalignment-map", ["--positions", "20"]),
    ("misalignment-map", ["--load-torque", "100"]), ("misalignment-map", ["--case-steps", "5"]),
    ("summary", ["--steady-state-after", "0.01"]), ("summary", ["--window", "0.01", "0.05"]),
    ("summary", ["--subgroup-size", "5"]), ("convergence", ["--steady-state-after", "0.01"]),
    ("speed-run", ["--pinion-speed", "2000"]), ("speed-run", ["--mesh-cycles", "50"]),
    ("speed-run", ["--min-window", "0.05"]), ("speed-run", ["--settle-time", "0.05"]),
    ("speed-run", ["--samples-per-mesh", "32"]), ("speed-run", ["--ramp-time", "0.05"]),
    ("sweep-run", ["--contact-model", "line"]),
]


@pytest.mark.parametrize("command, old", [
    pytest.param(*case.values, marks=case.marks, id=f"{case.values[0]} {case.values[1][0]}")
    if hasattr(case, "values") else pytest.param(*case, id=f"{case[0]} {case[1][0]}")
    for case in OLD])
def test_the_former_options_are_refused_by_argparse(world, command, old, capsys):
    with pytest.raises(SystemExit) as exit_:
        build_parser().parse_args(argv_of(world, command, *old))
    assert exit_.value.code == 2
    assert f"unrecognized arguments: {old[0]}" in capsys.readouterr().err
