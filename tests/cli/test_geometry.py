"""``lsbg geometry``: the files of one design point, design.json keys, round trip, errors."""

import json
import math

import numpy as np
import pytest

from lsbg import cli
from lsbg.solid import export, render
from lsbg.gear.design import CONFIG_KEYS, GearPairDesign
from lsbg.gear.geometry import GearPair
from lsbg.solid.polyhedra import read_stl

FILES = ("design.json", "flanks.nc", "pinion.stl", "gear.stl",
         "pair.urdf", "pair.png", "manifest.json", "pinion.step", "gear.step")
UNIT_SUFFIXES = ("_mm", "_mm3", "_deg", "_kg", "_kg_m2", "_kg_m3")
UNITLESS = {"pinion_teeth", "gear_teeth", "pinion_hand", "trace", "base_cone_rule",
            "base_cone_constant", "gear_ratio", "contact_ratio", "contact_ratio_profile",
            "contact_ratio_face", "lsbg_version", "mesh_triangles_pinion", "mesh_triangles_gear",
            "profile_shift", "thickness_modification", "undercut"}


@pytest.fixture(scope="module")
def geometry(tmp_path_factory):
    """Both traces written through the command line, once."""
    root = tmp_path_factory.mktemp("geometry")
    out = {}
    for trace in ("logarithmic", "circular"):
        out[trace] = root / trace
        assert cli.main(["geometry", "--set", f"design.trace={trace}",
                         "--set", "design.spiral_angle_deg=35", "--out", str(out[trace])]) == 0
    return out


def record(directory):
    with open(directory / "design.json", encoding="utf-8") as handle:
        return json.load(handle)


@pytest.mark.parametrize("trace", ["logarithmic", "circular"])
def test_geometry_writes_every_file(geometry, trace):
    directory = geometry[trace]
    assert sorted(p.name for p in directory.iterdir()) == sorted(FILES)
    assert not [p for p in directory.parent.iterdir() if p.name.startswith(".")]
    with open(directory / "pair.png", "rb") as handle:
        assert handle.read(8) == b"\x89PNG\r\n\x1a\n"
    rec = record(directory)
    for name in ("pinion", "gear"):
        mesh = read_stl(directory / f"{name}.stl")
        assert mesh.is_watertight and mesh.is_winding_consistent
        # the file's (single precision) solid has the volume of the record's mesh
        assert mesh.volume * 1e9 == pytest.approx(rec[f"volume_{name}_mm3"], rel=1e-6)


@pytest.mark.parametrize("trace", ["logarithmic", "circular"])
def test_design_json_keys_units_and_values(geometry, trace):
    rec = record(geometry[trace])
    for key in CONFIG_KEYS:
        assert key in rec
    documented = [
        "contact_ratio", "contact_ratio_profile", "contact_ratio_face",
        "undercut_pinion_deg", "undercut_gear_deg",
        "top_land_inner_pinion_mm", "top_land_outer_pinion_mm",
        "top_land_inner_gear_mm", "top_land_outer_gear_mm",
        "normal_pressure_angle_mean_deg", "spiral_angle_along_face_deg",
        "cone_distance_along_face_mm", "mass_pinion_kg", "mass_gear_kg",
        "axial_inertia_pinion_kg_m2", "axial_inertia_gear_kg_m2",
        "centre_of_mass_pinion_mm", "centre_of_mass_gear_mm", "lsbg_version",
    ]
    for key in documented + list(GearPairDesign().derived()):
        assert key in rec, key
    for key, value in rec.items():
        assert key in UNITLESS or key.endswith(UNIT_SUFFIXES), key
        assert isinstance(value, (int, float, str, list)), key
    assert rec["trace"] == trace
    assert rec["pitch_angle_pinion_deg"] == pytest.approx(13.6713, abs=5e-5)
    assert rec["outer_cone_distance_mm"] == pytest.approx(85.677, abs=5e-4)
    assert rec["normal_pressure_angle_mean_deg"] == pytest.approx(20.0, abs=0.05)
    assert rec["normal_pressure_angle_mean_deg"] == pytest.approx(
        rec["normal_pressure_angle_mean_design_deg"], abs=0.05)
    assert rec["undercut_pinion_deg"] == pytest.approx(0.5, abs=0.1)
    assert rec["contact_ratio"] == pytest.approx(
        rec["contact_ratio_profile"] + rec["contact_ratio_face"])
    assert len(rec["spiral_angle_along_face_deg"]) == len(rec["cone_distance_along_face_mm"]) == 21
    assert rec["cone_distance_along_face_mm"][0] == pytest.approx(rec["inner_cone_distance_mm"])
    assert rec["cone_distance_along_face_mm"][-1] == pytest.approx(rec["outer_cone_distance_mm"])
    for name in ("pinion", "gear"):
        assert rec[f"mass_{name}_kg"] == pytest.approx(rec[f"mass_quadrature_{name}_kg"], rel=5e-3)
        assert rec[f"axial_inertia_{name}_kg_m2"] == pytest.approx(
            rec[f"axial_inertia_quadrature_{name}_kg_m2"], rel=5e-3)
        assert len(rec[f"centre_of_mass_{name}_mm"]) == 3
        assert rec[f"top_land_outer_{name}_mm"] > rec[f"top_land_inner_{name}_mm"] > 0


def test_spiral_angle_along_face(geometry):
    lsbg_angle = record(geometry["logarithmic"])["spiral_angle_along_face_deg"]
    sbg_angle = record(geometry["circular"])["spiral_angle_along_face_deg"]
    assert np.ptp(lsbg_angle) < 0.01
    assert np.mean(lsbg_angle) == pytest.approx(35.0, abs=1e-6)
    assert np.ptp(sbg_angle) > 5
    assert sbg_angle[10] == pytest.approx(35.0, abs=1e-6)     # the mean point


def test_read_design_round_trips(geometry):
    assert export.read_design(geometry["logarithmic"]) == GearPairDesign()
    assert export.read_design(geometry["circular"]) == GearPairDesign(trace="circular")


@pytest.mark.parametrize("config", [
    {"spiral_angle_deg": 36.2},           # to_config gives 36.20000000000001
    {"spiral_angle_deg": 33.3, "normal_pressure_angle_deg": 21.7, "module_mm": 4.7,
     "face_width_mm": 23.1, "pinion_hand": "right", "trace": "circular"},
])
def test_exact_config_round_trips_through_json(config):
    design = GearPairDesign.from_config(config)
    text = json.dumps(design.to_config())
    assert GearPairDesign.from_config(json.loads(text)) == design


def test_read_design_after_write_geometry(tmp_path):
    design = GearPairDesign.from_config({"spiral_angle_deg": 36.8, "backlash_mm": 0.07})
    files = export.write_geometry(design, tmp_path / "point")
    assert export.read_design(files.directory) == design
    assert set(files.timings) == set(export.STAGES) | {"total"}
    assert sum(files.timings[s] for s in export.STAGES) <= files.timings["total"]


def test_flanks_netcdf_is_cf_and_matches_the_geometry(geometry):
    xr = pytest.importorskip("xarray")
    with xr.open_dataset(geometry["logarithmic"] / "flanks.nc") as ds:
        assert ds.attrs["Conventions"] == "CF-1.11"
        for key in ("title", "source", "history"):
            assert isinstance(ds.attrs[key], str) and ds.attrs[key]
        for value in ds.attrs.values():
            assert isinstance(value, (str, int, float, np.number))
        for name in ("point", "normal", "cone_distance", "profile", "polar_angle"):
            assert "units" in ds[name].attrs and "long_name" in ds[name].attrs
        assert ds["point"].dims == ("member", "side", "cone_distance", "profile", "xyz")
        pair = GearPair(GearPairDesign())
        sel = dict(member="gear", side="coast")
        radius = 1e-3 * ds["cone_distance"].values[5]
        polar = np.radians(ds["polar_angle"].sel(member="gear").values)
        expected, normals = pair.flank(2, "coast", radius, polar)
        np.testing.assert_allclose(ds["point"].sel(**sel).values[5], 1e3 * expected, atol=1e-9)
        np.testing.assert_allclose(ds["normal"].sel(**sel).values[5], normals, atol=1e-12)


def test_design_file_and_overrides(tmp_path, capsys):
    """A configuration file's design section, a key of it set over it; a bare mapping of
    design keys (the former --design FILE) is refused, naming the key."""
    design_file = tmp_path / "design.yaml"
    design_file.write_text("design:\n  trace: circular\n  spiral_angle_deg: 30\n"
                           "  face_width_mm: 22\n")
    out = tmp_path / "point"
    # (no STEP solids: test_geometry_writes_every_file has them)
    assert cli.main(["geometry", "--config", str(design_file), "--no-step",
                     "--set", "design.face_width_mm=24", "--out", str(out)]) == 0
    design = export.read_design(out)
    assert design == GearPairDesign.from_config(
        {"trace": "circular", "spiral_angle_deg": 30, "face_width_mm": 24})
    assert capsys.readouterr().out.startswith("lsbg geometry: circular, spiral angle 30 deg -> ")
    bare = tmp_path / "bare.yaml"
    bare.write_text("trace: circular\nspiral_angle_deg: 30\n")
    assert cli.main(["geometry", "--config", str(bare), "--out", str(tmp_path / "bad")]) == 2
    assert "spiral_angle_deg: unknown key (known: contact, cutter_sweep, design," in capsys.readouterr().err
    with pytest.raises(SystemExit) as exit_:
        cli.main(["geometry", "--design", str(design_file), "--out", str(tmp_path / "bad")])
    assert exit_.value.code == 2
    assert not (tmp_path / "bad").exists()


def test_every_design_key_can_be_set(capsys):
    """Every design key is a key of the schema's design section: ``--set design.KEY=VALUE``
    in the paper's units, YAML-typed (the former per-key options are gone)."""
    from lsbg.cli.options import design_of, settings_of
    from lsbg.config import load_schema

    from lsbg.gear.depth import TAPER_DEFAULTS

    assert {*CONFIG_KEYS, *TAPER_DEFAULTS} == set(
        load_schema()["properties"]["design"]["properties"])
    other = GearPairDesign.from_config({"trace": "circular", "spiral_angle_deg": 30,
                                        "module_mm": 5, "face_width_mm": 24,
                                        "pinion_hand": "right", "backlash_mm": 0.07,
                                        "depth_taper": "given_dedendum_angles",
                                        "dedendum_angles_deg": [2.5, 5]})
    parser = cli.build_parser()
    args = parser.parse_args(["geometry", "--out", "x"] + [
        arg for key, value in other.to_config().items()
        for arg in ("--set", f"design.{key}={value}")])
    assert design_of(settings_of(args)) == other
    with pytest.raises(SystemExit) as exit_:
        cli.main(["geometry", "--help"])
    assert exit_.value.code == 0
    help_text = " ".join(capsys.readouterr().out.split())
    for option in ("--config FILE.yaml", "--set SECTION.KEY=VALUE", "--relieved", "--no-step"):
        assert option in help_text, option
    assert "reads its sections design, flank_modification" in help_text
    assert "lsbg/schemas/config.schema.yaml" in help_text
    for old in ("--spiral-angle", "--module-mm", "--trace", "--design"):
        assert old not in help_text, old


def test_bad_spiral_angle_exits_2_and_writes_nothing(tmp_path, capsys):
    out = tmp_path / "bad"
    assert cli.main(["geometry", "--set", "design.trace=logarithmic",
                     "--set", "design.spiral_angle_deg=75", "--out", str(out)]) == 2
    assert ("design.spiral_angle_deg: 75 is greater than or equal to the maximum of 60"
            in capsys.readouterr().err)
    assert not out.exists()
    assert list(tmp_path.iterdir()) == []


def test_pointed_teeth_exit_2(tmp_path, capsys):
    out = tmp_path / "bad"
    assert cli.main(["geometry", "--set", "design.base_cone_rule=paper", "--out", str(out)]) == 2
    assert "base_cone_rule = 'paper': the pinion teeth come out pointed" in capsys.readouterr().err
    assert not out.exists()


def test_unknown_yaml_key_exits_2(tmp_path, capsys):
    design_file = tmp_path / "design.yaml"
    design_file.write_text("design:\n  spiral_angle_deg: 30\n  helix_angle_deg: 12\n")
    out = tmp_path / "bad"
    assert cli.main(["geometry", "--config", str(design_file), "--out", str(out)]) == 2
    assert "design.helix_angle_deg: unknown key (known: addendum_mm," in capsys.readouterr().err
    assert cli.main(["geometry", "--set", "design.helix_angle_deg=12", "--out", str(out)]) == 2
    assert ("--set 'design.helix_angle_deg=12': design.helix_angle_deg: unknown key"
            in capsys.readouterr().err)
    assert not out.exists()


def test_failure_leaves_nothing_half_written(tmp_path, monkeypatch):
    out = tmp_path / "point"
    out.mkdir()
    (out / "old.txt").write_text("previous run")

    def broken(*args, **kwargs):
        raise RuntimeError("renderer crashed")

    monkeypatch.setattr(render, "render_pair", broken)
    with pytest.raises(RuntimeError, match="renderer crashed"):
        export.write_geometry(GearPairDesign(), out)
    # the previous output is untouched and no temporary directory is left
    assert [p.name for p in tmp_path.iterdir()] == ["point"]
    assert [p.name for p in out.iterdir()] == ["old.txt"]


def test_urdf_of_the_stage_loads_in_pybullet(geometry):
    p = pytest.importorskip("pybullet")
    rec = record(geometry["circular"])
    client = p.connect(p.DIRECT)
    try:
        body = p.loadURDF(str(geometry["circular"] / "pair.urdf"), useFixedBase=True,
                          flags=p.URDF_USE_INERTIA_FROM_FILE, physicsClientId=client)
        for j, name in enumerate(("pinion", "gear")):
            dyn = p.getDynamicsInfo(body, j, physicsClientId=client)
            assert dyn[0] == pytest.approx(rec[f"mass_{name}_kg"], rel=1e-12)
            assert dyn[2][2] == pytest.approx(rec[f"axial_inertia_{name}_kg_m2"], rel=1e-6)
            np.testing.assert_allclose(1e3 * np.array(dyn[3]), rec[f"centre_of_mass_{name}_mm"],
                                       atol=1e-9)
        # the visual meshes resolve relative to the URDF
        shapes = p.getVisualShapeData(body, physicsClientId=client)
        assert {s[1] for s in shapes} >= {0, 1}
    finally:
        p.disconnect(client)


def test_spiral_angle_setting_is_degrees():
    from lsbg.cli.options import design_of, settings_of

    args = cli.build_parser().parse_args(["geometry", "--set", "design.spiral_angle_deg=30",
                                          "--out", "x"])
    assert math.degrees(design_of(settings_of(args)).spiral_angle) == pytest.approx(30)


def test_a_new_module_of_lsbg_cli_is_a_new_subcommand(monkeypatch, capsys, tmp_path):
    """A module of lsbg.cli with an ``add_<name>_parser`` in its ``__all__`` is a subcommand
    (as lsbg.cli's docstring shows), nothing registered: its configuration resolved before
    its handler, its line printed."""
    monkeypatch.setattr(cli, "__path__", [*cli.__path__, str(tmp_path)])
    (tmp_path / "hello.py").write_text(
        "from lsbg.cli.options import add_config_options, design_of\n"
        "__all__ = ['add_hello_parser']\n\n"
        "def hello(args):\n"
        "    teeth = design_of(args.settings).pinion_teeth\n"
        "    return 7 if teeth == 11 else f'{teeth} pinion teeth'\n\n"
        "def add_hello_parser(subparsers):\n"
        "    parser = subparsers.add_parser('hello')\n"
        "    add_config_options(parser, ('design',))\n"
        "    parser.set_defaults(handler=hello)\n")
    assert cli.main(["hello", "--set", "design.pinion_teeth=11"]) == 7
    assert cli.main(["hello", "--set", "design.pinion_teeth=13"]) == 0
    assert capsys.readouterr().out == "lsbg hello: 13 pinion teeth\n"
    assert cli.main(["hello", "--set", "design.pinion_teeth=x"]) == 2
    assert capsys.readouterr().err == ("lsbg hello: error: design.pinion_teeth: 'x' is not of "
                                       "type 'integer'\n")


# ---------------------------------------------------------------- simulate
def test_simulate_writes_a_run_and_rejects_bad_settings(tmp_path, capsys):
    main = cli.main
    import xarray as xr

    geo = tmp_path / "geo"
    assert main(["geometry", "--set", "design.trace=logarithmic", "--no-step",
                 "--set", "design.spiral_angle_deg=35", "--out", str(geo)]) == 0
    out = tmp_path / "run.nc"
    assert main(["simulate", "--geometry", str(geo), "--engine", "scipy",
                 "--set", "simulation.duration_s=0.02", "--set", "simulation.samples=10",
                 "--set", "simulation.ramp_time_s=0.01",
                 "--set", "simulation.full_rate_after_s=0.01", "--out", str(out)]) == 0
    ds = xr.open_dataset(out)
    assert ds.time.size == 11 and ds.gear_speed.attrs["units"] == "deg/s"
    ds.close()
    bad = tmp_path / "bad.nc"
    assert main(["simulate", "--geometry", str(geo), "--set", "simulation.duration_s=-1",
                 "--out", str(bad)]) == 2
    assert ("simulation.duration_s: -1 is less than or equal to the minimum of 0"
            in capsys.readouterr().err)
    config = tmp_path / "study.yaml"
    config.write_text("contact:\n  static_friction: 3\n")
    assert main(["simulate", "--geometry", str(geo), "--config", str(config), "--out", str(bad)]) == 2
    assert "contact.static_friction: 3 is greater than the maximum of 1" in capsys.readouterr().err
    # a blow-up (time step far too coarse) stops with exit code 3 and leaves no file
    assert main(["simulate", "--geometry", str(geo), "--set", "simulation.duration_s=0.01",
                 "--set", "simulation.samples=5", "--set", "simulation.ramp_time_s=0.005",
                 "--set", "simulation.time_step_s=1e-4", "--set", "simulation.full_rate_hz=5000",
                 "--set", "simulation.full_rate_after_s=0.004", "--out", str(bad)]) == 3
    assert "simulation stopped" in capsys.readouterr().err
    assert not bad.exists() and not list(tmp_path.glob("*.part"))
