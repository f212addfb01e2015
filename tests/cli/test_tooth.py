"""The tooth's own compliance through the command line and the configuration: `lsbg
compliance` (computed once, kept), `lsbg ltca --set contact.compliance=fe` (the line model on
the slice
stiffness reproduces the complementarity LTCA), a line-model run on it, `compliance:
uniform` leaving today's LTCA as it was, and bad input named before any work."""

import copy
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml

from lsbg import cli
from lsbg.gear.design import GearPairDesign
from lsbg.solid.export import write_geometry
from lsbg.tooth.config import tooth_from_config

REPO = Path(__file__).resolve().parents[2]
#: A coarse FE model: the suite's budget (the default mesh is checked in tests/tooth/test_ltca.py).
COARSE = ["--set", "tooth.element_size_module=0.52", "--set", "tooth.rim_element_factor=10",
          "--set", "tooth.face_points=5", "--set", "tooth.profile_points=5"]
#: The FE loaded TCA: the tooth's own compliance, at 48 mesh positions.
FE = ["--set", "contact.compliance=fe", "--set", "tooth.ltca_positions=48"]


@pytest.fixture(scope="module")
def point(tmp_path_factory):
    """The paper's LSBG: geometry, coarse FE compliance and the FE loaded TCA via the CLI."""
    root = tmp_path_factory.mktemp("tooth_cli")
    geo = root / "logarithmic_beta35"
    write_geometry(GearPairDesign(), geo)
    config = root / "config.yaml"
    config.write_text(yaml.safe_dump({"flank_modification": {"lengthwise_crowning_um": 25,
                                                              "profile_crowning_um": 5}}))
    files = {"root": root, "geo": geo, "config": config, "compliance": root / "c.nc",
             "fe": root / "fe.nc"}
    assert cli.main(["compliance", "--geometry", str(geo), *COARSE,
                     "--out", str(files["compliance"])]) == 0
    assert cli.main(["ltca", "--geometry", str(geo), "--config", str(config), *FE,
                     "--compliance-file", str(files["compliance"]), *COARSE,
                     "--out", str(files["fe"])]) == 0
    return files


def test_the_compliance_is_computed_once_and_kept(point, capsys):
    before = point["compliance"].stat().st_mtime_ns
    capsys.readouterr()
    assert cli.main(["compliance", "--geometry", str(point["geo"]), *COARSE,
                     "--out", str(point["compliance"])]) == 0
    assert "kept (same inputs)" in capsys.readouterr().out
    assert point["compliance"].stat().st_mtime_ns == before
    # another material: other inputs, computed again (and it says so)
    other = point["root"] / "other.nc"
    with xr.open_dataset(point["compliance"]) as first:
        hash_ = first.attrs["inputs_hash"]
    assert cli.main(["compliance", "--geometry", str(point["geo"]), *COARSE,
                     "--set", "tooth.young_modulus_GPa=103", "--out", str(other)]) == 0
    with xr.open_dataset(other) as second, xr.open_dataset(point["compliance"]) as first:
        assert second.attrs["inputs_hash"] != hash_
        # half the modulus: twice the compliance (linear elasticity, same mesh and nu)
        c1, c2 = first["compliance_gear"].values, second["compliance_gear"].values
        big = np.abs(c1) > 0.1 * np.abs(c1).max()
        np.testing.assert_allclose(c2[big] / c1[big], 206 / 103, rtol=1e-6)


def test_the_fe_ltca_carries_stresses_and_a_slice_stiffness_that_reproduces_it(point):
    with xr.open_dataset(point["fe"]) as ds:
        ds = ds.load()
    assert ds.attrs["compliance"] == "fe" and ds.attrs["contact_compliance"] == "fe"
    assert ds.sizes["mesh_phase"] == 48                       # tooth.ltca_positions
    for name, unit in {"transmission_error": "urad", "mesh_stiffness": "N/um",
                       "max_contact_pressure": "MPa", "root_stress_pinion": "MPa",
                       "root_stress_gear": "MPa", "contact_pattern": "N/mm",
                       "slice_stiffness": "N/(mm um)"}.items():
        assert ds[name].attrs["units"] == unit, name
    # the line model on the slice stiffness reproduces the complementarity solution
    p2p = float(np.ptp(ds["transmission_error"].values))
    assert ds.attrs["slice_table_transmission_error_difference_urad"] < 1e-3 * p2p
    # a bevel tooth is not a uniform bed: its stiffness varies over the face and cycle
    k = ds["slice_stiffness"].values
    assert np.all(k > 0) and k.max() / k.min() > 1.5
    assert 5 < float(np.median(k)) < 50         # N/(mm um): the order of ISO's c_gamma
    assert ds.attrs["max_root_stress_pinion_MPa"] > 0 and ds.attrs["max_root_stress_gear_MPa"] > 0


def test_a_line_model_run_takes_the_slice_stiffness(point):
    run = point["root"] / "run.nc"
    common = ["simulate", "--geometry", str(point["geo"]), "--config", str(point["config"]),
              "--engine", "compiled", "--set", "contact.model=line",
              "--set", "simulation.duration_s=0.03", "--set", "simulation.samples=30",
              "--set", "simulation.ramp_time_s=0.01", "--set", "simulation.full_rate_hz=2000",
              "--set", "simulation.full_rate_after_s=0.01"]
    assert cli.main([*common, "--set", "contact.compliance=fe", "--fe-ltca", str(point["fe"]),
                     "--out", str(run)]) == 0
    with xr.open_dataset(run) as ds, xr.open_dataset(point["fe"]) as fe:
        assert ds.attrs["contact_compliance"] == "fe"
        assert ds.attrs["slice_stiffness_compliance_inputs_hash"] == fe.attrs[
            "compliance_inputs_hash"]
        # the mesh mode's frequency follows the FE mean stiffness, below the uniform bed's
        assert 0.5 < ds.attrs["mean_mesh_stiffness_N_per_m"] / (
            fe.attrs["mesh_stiffness_mean_N_per_um"] * 1e6) < 1.5


def test_compliance_uniform_leaves_todays_ltca(point, tmp_path):
    config = yaml.safe_load(point["config"].read_text())
    uniform = tmp_path / "uniform.yaml"
    uniform.write_text(yaml.safe_dump({**config, "contact": {"compliance": "uniform"}}))
    a, b = tmp_path / "a.nc", tmp_path / "b.nc"
    for cfg, out in ((point["config"], a), (uniform, b)):
        assert cli.main(["ltca", "--geometry", str(point["geo"]), "--config", str(cfg),
                         "--set", "tca.loaded_positions=32", "--out", str(out)]) == 0
    with xr.open_dataset(a) as da, xr.open_dataset(b) as db:
        for name in ("transmission_error", "mesh_stiffness", "contact_pattern", "pair_load"):
            np.testing.assert_allclose(db[name].values, da[name].values, rtol=1e-6, atol=0)


@pytest.mark.parametrize("argv, message", [
    (["ltca", "--set", "contact.compliance=fe"],
     "contact.compliance = 'fe' needs --compliance-file"),
    (["simulate", "--set", "contact.model=line", "--set", "contact.compliance=fe"],
     "contact.compliance = 'fe': a line-model run needs --fe-ltca"),
    (["compliance", "--set", "tooth.poisson_ratio=0.5"],
     "tooth.poisson_ratio: 0.5 is greater than or equal to the maximum of 0.5"),
    (["compliance", "--set", "tooth.young_modulus_GPa=5000"],
     "tooth.young_modulus_GPa: 5000 is greater than the maximum of 1000"),
    (["compliance", "--set", "tooth.element_size_module=0.8"],
     "tooth.element_size_module: 0.8 is greater than the maximum of"),
    (["compliance", "--set", "tooth.face_points=4.5"],
     "tooth.face_points: 4.5 is not of type 'integer'"),
    (["compliance", "--set", "tooth.rim_size=3"],
     "--set 'tooth.rim_size=3': tooth.rim_size: unknown key (known: element_size_module,"),
])
def test_bad_input_is_named_before_any_work(point, capsys, argv, message):
    out = point["root"] / "never.nc"
    code = cli.main([argv[0], "--geometry", str(point["geo"]), *argv[1:], "--out", str(out)])
    assert code == 2
    assert message in capsys.readouterr().err
    assert not out.exists()


def test_a_slice_stiffness_of_another_load_is_refused(point, capsys):
    out = point["root"] / "never.nc"
    code = cli.main(["simulate", "--geometry", str(point["geo"]), "--set", "contact.model=line",
                     "--set", "contact.compliance=fe", "--fe-ltca", str(point["fe"]),
                     "--set", "simulation.load_torque_N_m=1000", "--out", str(out)])
    assert code == 2 and "secant at its own load" in capsys.readouterr().err
    assert not out.exists()


def deep_update(base, over):
    """``over`` merged into ``base`` section by section, as Snakemake merges config files."""
    out = copy.deepcopy(base)
    for key, value in over.items():
        out[key] = (deep_update(out[key], value) if isinstance(value, dict)
                    and isinstance(out.get(key), dict) else copy.deepcopy(value))
    return out


def test_the_configuration_check_names_the_tooth_keys():
    from lsbg.study.checks import check_config, one_spiral_angle

    schema = yaml.safe_load((REPO / "lsbg/schemas/config.schema.yaml").read_text())
    base = yaml.safe_load((REPO / "workflow/config.yaml").read_text())
    test = yaml.safe_load((REPO / "workflow/config-test.yaml").read_text())
    merged = deep_update(base, test)
    assert one_spiral_angle(merged, test) == []   # the test study's one angle, as the workflow

    def problems(**changes):
        config = copy.deepcopy(merged)
        for path, value in changes.items():
            section, key = path.split("__")
            config.setdefault(section, {})[key] = value
        return "\n".join(check_config(config, schema))

    assert "tooth.young_modulus_GPa" in problems(tooth__young_modulus_GPa=5000)
    assert "tooth.poisson_ratio" in problems(tooth__poisson_ratio=0.5)
    same = problems(sensitivity__compliance=["uniform"])
    assert "sensitivity.compliance[0] = 'uniform': the same as contact.compliance" in same
    # the resource guard: a mesh too fine for the time the rules grant
    fine = problems(tooth__element_size_module=0.1, limits__tooth_minutes=0.5)
    assert "tooth.element_size_module = 0.1: the FE compliance of" in fine
    assert "limits.tooth_minutes = 0.5" in fine
    # root fillets too wide for the 37-tooth gear's gaps at 45 deg (its root is
    # 1.7 mm wide at the toe): named before any job, both traces
    wide = problems(contact__compliance="fe", sweep__spiral_angles_deg=[35, 45],
                    tooth__fillet_radius_module=0.34)
    for trace in ("logarithmic", "circular"):
        assert (f"tooth.fillet_radius_module = 0.34: {trace} 45 deg: the gear's root fillets "
                "do not fit") in wide
    assert "35 deg: the" not in wide
    assert problems() == ""


def test_tooth_section_in_si():
    material, mesh, positions = tooth_from_config({"young_modulus_GPa": 210, "poisson_ratio": 0.29,
                                                   "element_size_module": 0.5,
                                                   "ltca_positions": 120})
    assert material.young_modulus == pytest.approx(2.1e11) and material.poisson_ratio == 0.29
    assert mesh.tooth_size == 0.5 and positions == 120


def test_points_under_compliance_fe_reuse_the_compliance_and_run_on_it(point, tmp_path):
    """`lsbg points` (the sweep's batch job) under compliance fe: the design point's
    compliance is kept (same inputs), its loaded TCA is the FE one, its line run takes
    that slice stiffness."""
    config = tmp_path / "fe.yaml"
    config.write_text(yaml.safe_dump({
        **yaml.safe_load(point["config"].read_text()),
        "contact": {"compliance": "fe"},
        "simulation": {"duration_s": 0.02, "samples": 20, "ramp_time_s": 0.01,
                       "full_rate_hz": 2000, "full_rate_after_s": 0.01},
        "tooth": {"element_size_module": 0.52, "rim_element_factor": 10, "face_points": 5,
                  "profile_points": 5, "ltca_positions": 48}}))
    compliance = tmp_path / "logarithmic_beta{spiral}_compliance.nc"
    (tmp_path / "logarithmic_beta35_compliance.nc").write_bytes(point["compliance"].read_bytes())
    before = (tmp_path / "logarithmic_beta35_compliance.nc").stat().st_mtime_ns
    assert cli.main(["points", "--set", "design.trace=logarithmic", "--spiral-angles", "35",
                     "--config", str(config), "--geometry-out", str(tmp_path / "geo{spiral}"),
                     "--mesh-out", str(tmp_path / "mesh{spiral}.nc"),
                     "--compliance-out", str(compliance),
                     "--run", f"line={tmp_path / 'line{spiral}.nc'}"]) == 0
    assert (tmp_path / "logarithmic_beta35_compliance.nc").stat().st_mtime_ns == before
    with xr.open_dataset(tmp_path / "mesh35.nc") as mesh, \
            xr.open_dataset(tmp_path / "line35.nc") as run, xr.open_dataset(point["fe"]) as fe:
        assert mesh.attrs["compliance"] == "fe" and "slice_stiffness" in mesh
        # the same design point, flanks and FE model as `lsbg ltca` under compliance fe
        np.testing.assert_allclose(mesh["transmission_error"].values,
                                   fe["transmission_error"].values, rtol=1e-9)
        assert run.attrs["slice_stiffness_compliance_inputs_hash"] == mesh.attrs[
            "compliance_inputs_hash"]


def test_points_under_compliance_fe_need_the_compliance_template(point, tmp_path, capsys):
    config = tmp_path / "fe.yaml"
    config.write_text(yaml.safe_dump({"contact": {"compliance": "fe"}}))
    code = cli.main(["points", "--set", "design.trace=logarithmic", "--spiral-angles", "35",
                     "--config", str(config), "--geometry-out", str(tmp_path / "geo{spiral}"),
                     "--mesh-out", str(tmp_path / "mesh{spiral}.nc")])
    assert code == 2 and "needs --compliance-out" in capsys.readouterr().err
    assert not (tmp_path / "geo35").exists()


def test_the_envelope_and_the_rating_beside_the_fe_stresses(point, tmp_path, capsys):
    """`lsbg ltca --envelope`: the FE loaded TCA at the four corners of E and P at +-0.1
    mm; the aligned assembly lies inside them, so the worst corner's largest pressure is
    no smaller than the aligned one's less the sampling of 48 positions. `lsbg rate` puts
    both beside ISO 10300."""
    envelope = tmp_path / "envelope.nc"
    assert cli.main(["ltca", "--geometry", str(point["geo"]), "--config", str(point["config"]),
                     *FE, "--compliance-file", str(point["compliance"]),
                     *COARSE, "--envelope", "--out", str(envelope)]) == 0
    with xr.open_dataset(envelope) as env, xr.open_dataset(point["fe"]) as aligned:
        assert list(env["corner"].values) == ["E+0.1 P+0.1", "E+0.1 P-0.1", "E-0.1 P+0.1",
                                              "E-0.1 P-0.1"]
        assert env["displacement"].sel(corner="E-0.1 P+0.1").values.tolist() == [-0.1, 0.1]
        worst = float(env["max_contact_pressure"].max())
        assert worst >= 0.9 * float(aligned["max_contact_pressure"].max())
        # the corners differ: displacement moves the load
        peaks = env["max_contact_pressure"].max("mesh_phase").values
        assert np.ptp(peaks) > 0.01 * peaks.max()
    rating = tmp_path / "rating.nc"
    assert cli.main(["rate", "--geometry", str(point["geo"]), "--config", str(point["config"]),
                     "--fe-ltca", str(point["fe"]), "--fe-envelope", str(envelope),
                     "--out", str(rating)]) == 0
    with xr.open_dataset(rating) as ds:
        assert float(ds["fe_displaced_max_contact_pressure"].max()) == pytest.approx(worst)
        assert ds["contact_safety"].sel(member="pinion") < 1  # the paper's load: 4x the rating
        assert ds.attrs["dynamic_factor_source"].startswith("K_v = 1")
    # the envelope needs the FE compliance; an envelope of another load is refused
    capsys.readouterr()
    assert cli.main(["ltca", "--geometry", str(point["geo"]), "--envelope", "--out",
                     str(tmp_path / "x.nc")]) == 2
    assert "--envelope: needs the FE compliance" in capsys.readouterr().err
    other = tmp_path / "other.yaml"
    other.write_text(yaml.safe_dump({"simulation": {"load_torque_N_m": 1000}}))
    assert cli.main(["rate", "--geometry", str(point["geo"]), "--config", str(other),
                     "--fe-envelope", str(envelope), "--out", str(tmp_path / "z.nc")]) == 2
    assert "computed at 1964.99 N m, the rating's load is 1000 N m" in capsys.readouterr().err
    assert not (tmp_path / "x.nc").exists() and not (tmp_path / "z.nc").exists()


def test_a_case_run_rates_the_pair_with_its_own_dynamic_factor(point, tmp_path):
    """`lsbg rate --case-run`: the pair rated again with each case run's K_v is the
    rating with that K_v given as a number (rating.dynamic_factor), and the cases
    differ from the base only where K_v does."""
    from lsbg.aggregate.summary import run_dynamic_factor

    runs = {}
    for name, damping in (("base", 0.05), ("mesh_damping_ratio_x0.2", 0.01)):
        runs[name] = tmp_path / f"{name}.nc"
        assert cli.main(["simulate", "--geometry", str(point["geo"]), "--engine", "compiled",
                         "--set", "contact.model=line", "--set", "simulation.duration_s=0.06",
                         "--set", "simulation.ramp_time_s=0.01", "--set", "simulation.samples=30",
                         "--set", "simulation.full_rate_after_s=0.02",
                         "--set", f"contact.mesh_damping_ratio={damping}",
                         "--out", str(runs[name])]) == 0
    rating = tmp_path / "rating.nc"
    # the study's steady state (0.2 s) is beyond these short runs: said, not a traceback
    assert cli.main(["rate", "--geometry", str(point["geo"]), "--run", str(runs["base"]),
                     "--out", str(rating)]) == 2
    assert not rating.exists()
    steady = tmp_path / "steady.yaml"
    steady.write_text(yaml.safe_dump({"statistics": {"steady_state_after_s": 0.02}}))
    assert cli.main(["rate", "--geometry", str(point["geo"]), "--config", str(steady),
                     "--run", str(runs["base"]),
                     "--case-run", f"mesh_damping_ratio_x0.2={runs['mesh_damping_ratio_x0.2']}",
                     "--out", str(rating)]) == 0
    with xr.open_dataset(runs["mesh_damping_ratio_x0.2"]) as run:
        kv = max(run_dynamic_factor(run, 0.02), 1.0)
    given = tmp_path / "given.nc"
    assert cli.main(["rate", "--geometry", str(point["geo"]), "--set",
                     f"rating.dynamic_factor={kv!r}", "--out", str(given)]) == 0
    with xr.open_dataset(rating) as ds, xr.open_dataset(given) as direct:
        case = ds.sel(case="mesh_damping_ratio_x0.2")
        assert float(case["case_dynamic_factor"]) == pytest.approx(kv, rel=1e-12)
        assert float(case["case_contact_stress"]) == pytest.approx(
            float(direct["contact_stress"]), rel=1e-12)
        np.testing.assert_allclose(case["case_root_stress"], direct["root_stress"], rtol=1e-12)
        assert kv != pytest.approx(float(ds.attrs["factor_K_v"]), rel=1e-6)
