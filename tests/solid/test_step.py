"""The exact solids as STEP (lsbg.solid.step), read back with OpenCASCADE.

Each member is one closed solid (every edge of its boundary shared by two
faces); its volume agrees with the quadrature of the exact solid
(lsbg.solid.mass.quadrature_mass_properties) within 0.5 %; the exact flanks lie
within 1 µm of its surface at 200 random points per side; a rerun writes the
same bytes; and `lsbg geometry` lists the files in its manifest, which then
guards them like the others. With a flank modification and `--relieved` the
pinion's solid is the relieved flank, within 1 µm, and the gear's is unchanged;
without `--relieved` both are the conjugate solids whatever the section says.
"""

import hashlib

import pytest

from lsbg import cli

from lsbg.gear.design import GearPairDesign
from lsbg.solid.export import write_geometry
from lsbg.files import InputError
from lsbg.solid.directory import read_design
from lsbg.gear.geometry import GearPair
from lsbg.solid.mass import quadrature_mass_properties
from lsbg.solid.step import flank_deviation, read_step, write_step


@pytest.fixture(scope="module")
def geometry(tmp_path_factory):
    """The paper's LSBG written with its STEP solids."""
    out = tmp_path_factory.mktemp("step") / "logarithmic_beta35"
    write_geometry(GearPairDesign(), out, step=True)
    return out


@pytest.fixture(scope="module")
def sbg_steps(tmp_path_factory):
    pair = GearPair(GearPairDesign(trace="circular"))
    root = tmp_path_factory.mktemp("step_sbg")
    return pair, {m: write_step(pair, m, root / f"{m}.step") for m in (1, 2)}


def _check_member(pair, member, path):
    solid = read_step(path)
    assert solid["volumes"] == 1 and solid["open_edges"] == 0
    exact = quadrature_mass_properties(pair, member).volume
    assert solid["volume"] == pytest.approx(exact, rel=5e-3)
    deviation = flank_deviation(pair, member, path, points=200)
    assert deviation.size == 400 and deviation.max() < 1e-6


@pytest.mark.parametrize("member, name", [(1, "pinion"), (2, "gear")])
def test_lsbg_solids_are_closed_of_the_right_volume_and_flanks(geometry, member, name):
    _check_member(GearPair(read_design(geometry)), member, geometry / f"{name}.step")


@pytest.mark.parametrize("member", [1, 2])
def test_sbg_solids_are_closed_of_the_right_volume_and_flanks(sbg_steps, member):
    pair, paths = sbg_steps
    _check_member(pair, member, paths[member])


def test_a_rerun_writes_the_same_bytes(geometry, tmp_path):
    again = write_step(GearPair(GearPairDesign()), 1, tmp_path / "pinion.step")
    digest = [hashlib.sha256(p.read_bytes()).hexdigest() for p in (geometry / "pinion.step", again)]
    assert digest[0] == digest[1]
    header = again.read_text(encoding="utf-8")[:600]
    assert "2000-01-01T00:00:00" in header and "PRODUCT('lsbg pinion'" in again.read_text()


def test_the_manifest_lists_and_guards_the_step_files(geometry, tmp_path):
    import json
    import shutil

    files = json.loads((geometry / "manifest.json").read_text(encoding="utf-8"))["files"]
    assert {"pinion.step", "gear.step"} <= set(files)
    edited = shutil.copytree(geometry, tmp_path / "logarithmic_beta35")
    with open(edited / "gear.step", "a", encoding="utf-8") as handle:
        handle.write("\n")
    with pytest.raises(InputError, match=r"gear.step: changed since 'lsbg geometry' wrote it"):
        read_design(edited)
    # without them (lsbg points, lsbg geometry --no-step) a directory is complete too
    plain = tmp_path / "plain" / "logarithmic_beta35"
    write_geometry(GearPairDesign(), plain)
    assert not (plain / "pinion.step").exists() and read_design(plain).trace == "logarithmic"


def test_geometry_relieves_the_pinion_step_solid_by_the_modification(geometry, tmp_path):
    from lsbg.tca.modification import FlankModification, pinion_relief

    out = tmp_path / "logarithmic_beta35"
    crowned = ["geometry", "--set", "design.trace=logarithmic",
               "--set", "design.spiral_angle_deg=35",
               "--set", "flank_modification.lengthwise_crowning_um=25",
               "--set", "flank_modification.profile_crowning_um=5"]
    assert cli.main([*crowned, "--relieved", "--out", str(out)]) == 0
    pair = GearPair(read_design(out))
    modification = FlankModification(25e-6, 5e-6)

    def relief(rho, polar):
        return pinion_relief(pair, modification, rho, polar)

    relieved = flank_deviation(pair, 1, out / "pinion.step", points=100, relief=relief)
    assert relieved.max() < 1e-6
    conjugate = flank_deviation(pair, 1, out / "pinion.step", points=100)
    # drive points: off the conjugate flank by the relief (up to C_L + C_P near the
    # corners); coast points: on it
    assert 20e-6 < conjugate[:100].max() < 31e-6 and conjugate[100:].max() < 1e-6
    assert (out / "gear.step").read_bytes() == (geometry / "gear.step").read_bytes()
    # without --relieved the section is read by nothing: the conjugate solids
    plain = tmp_path / "plain" / "logarithmic_beta35"
    assert cli.main([*crowned, "--out", str(plain)]) == 0
    for name in ("pinion.step", "gear.step"):
        assert (plain / name).read_bytes() == (geometry / name).read_bytes(), name
