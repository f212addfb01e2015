"""Inputs that prove what they are: the manifest of a geometry directory, checked NetCDF
reading, and the temporaries a killed writer leaves (removed by the next writer)."""

import json
import os
import shutil
import signal
import subprocess
import sys
import time

import numpy as np
import pytest
from pathlib import Path
import xarray as xr

from lsbg import files
from lsbg.solid import directory as geometry_files
from lsbg.gear.design import GearPairDesign
from lsbg.solid.export import write_geometry
from lsbg.files import InputError, InputFileNotFoundError
from lsbg.files import open_dataset, short_labels, write_atomically, write_dataset


@pytest.fixture(scope="module")
def geometry(tmp_path_factory):
    """The paper's LSBG design point, in a directory named as the workflow names it."""
    out = tmp_path_factory.mktemp("files") / "logarithmic_beta35"
    write_geometry(GearPairDesign(), out)
    return out


@pytest.fixture
def copy(geometry, tmp_path):
    """A fresh copy of the geometry directory to tamper with."""
    def make(name=geometry.name):
        return shutil.copytree(geometry, tmp_path / name)
    return make


def rehash(directory, name):
    """Update the manifest's entry of ``name`` as if lsbg had written the file (a forged
    manifest: only the checks after the hashes can catch what was edited)."""
    path = directory / geometry_files.MANIFEST
    manifest = json.loads(path.read_text(encoding="utf-8"))
    manifest["files"][name] = {"bytes": (directory / name).stat().st_size,
                               "sha256": files.file_digest(directory / name)}
    path.write_text(json.dumps(manifest), encoding="utf-8")


def edit_record(directory, **changes):
    path = directory / "design.json"
    record = json.loads(path.read_text(encoding="utf-8"))
    for key, value in changes.items():
        if value is None:
            del record[key]
        else:
            record[key] = value
    path.write_text(json.dumps(record, indent=1), encoding="utf-8")


# ----------------------------------------------------------------- manifest
def test_manifest_lists_every_file_and_the_design_point(geometry):
    manifest = json.loads((geometry / geometry_files.MANIFEST).read_text(encoding="utf-8"))
    assert manifest["format"] == geometry_files.MANIFEST_FORMAT
    assert manifest["design_point"] == {"trace": "logarithmic", "spiral_angle_deg": 35.0}
    assert manifest["design_sha256"] == geometry_files.design_digest(GearPairDesign().to_config())
    assert sorted(manifest["files"]) == sorted(geometry_files.FILE_NAMES.values())
    for name, entry in manifest["files"].items():
        assert entry == {"bytes": (geometry / name).stat().st_size,
                         "sha256": files.file_digest(geometry / name)}
    assert geometry_files.read_design(geometry) == GearPairDesign()


def test_manifest_is_deterministic(copy):
    """No time stamp: the same files give the same manifest, byte for byte."""
    directory = copy()
    before = (directory / geometry_files.MANIFEST).read_bytes()
    (directory / geometry_files.MANIFEST).unlink()
    geometry_files.write_manifest(directory)
    assert (directory / geometry_files.MANIFEST).read_bytes() == before


def test_rerun_writes_the_same_bytes(geometry, tmp_path):
    """Deterministic output: a rerun of the same design point gives the same directory,
    manifest included, byte for byte."""
    again = write_geometry(GearPairDesign(), tmp_path / geometry.name).directory
    names = sorted(p.name for p in geometry.iterdir())
    assert sorted(p.name for p in again.iterdir()) == names
    for name in names:
        assert (again / name).read_bytes() == (geometry / name).read_bytes(), name


def test_design_digest_tells_design_points_apart():
    paper = GearPairDesign().to_config()
    assert geometry_files.design_digest(paper) == geometry_files.design_digest(dict(reversed(paper.items())))
    assert geometry_files.design_digest(paper) != geometry_files.design_digest({**paper, "spiral_angle_deg": 40.0})


def _spiral_40(d):
    edit_record(d, spiral_angle_deg=40.0)


def _garbage_design(d):
    (d / "design.json").write_text("{not json", encoding="utf-8")


def _truncate_stl(d):
    with open(d / "gear.stl", "r+b") as handle:
        handle.truncate(1000)


def _flip_stl_byte(d):
    data = bytearray((d / "pinion.stl").read_bytes())
    data[len(data) // 2] ^= 0x01                        # same size, one bit
    (d / "pinion.stl").write_bytes(bytes(data))


def _forged_garbage(d):
    _garbage_design(d)
    rehash(d, "design.json")


def _forged_missing_key(d):
    edit_record(d, axial_inertia_gear_kg_m2=None)
    rehash(d, "design.json")


def _forged_spiral_40(d):
    _spiral_40(d)
    rehash(d, "design.json")


def _manifest_without_urdf(d):
    manifest = json.loads((d / geometry_files.MANIFEST).read_text(encoding="utf-8"))
    del manifest["files"]["pair.urdf"]
    (d / geometry_files.MANIFEST).write_text(json.dumps(manifest), encoding="utf-8")


TAMPERED = {
    # what was done -> (change, the file named, what the message says)
    "spiral angle 35 -> 40": (_spiral_40, "design.json", "changed since 'lsbg geometry'"),
    "garbage design.json": (_garbage_design, "design.json", "changed since"),
    "truncated STL": (_truncate_stl, "gear.stl", "changed since"),
    "one bit of an STL": (_flip_stl_byte, "pinion.stl", "changed since"),
    "URDF deleted": (lambda d: (d / "pair.urdf").unlink(), "pair.urdf", "missing"),
    "manifest deleted": (lambda d: (d / geometry_files.MANIFEST).unlink(), "logarithmic_beta35",
                         "no manifest.json"),
    "garbage manifest": (lambda d: (d / geometry_files.MANIFEST).write_bytes(b"\xff\xfe"),
                         "manifest.json", "not valid JSON"),
    "manifest lacks a file": (_manifest_without_urdf, "manifest.json", "not a manifest"),
    # the manifest forged to match: the checks after the hashes
    "forged: garbage design.json": (_forged_garbage, "design.json", "not valid JSON (line 1)"),
    "forged: missing key": (_forged_missing_key, "design.json",
                            "missing ['axial_inertia_gear_kg_m2']"),
    "forged: spiral angle 35 -> 40": (_forged_spiral_40, "design.json",
                                      "not the design point of manifest.json"),
}


@pytest.mark.parametrize("case", TAMPERED)
def test_tampered_directory_is_named_with_how_to_regenerate(copy, case):
    change, named, says = TAMPERED[case]
    directory = copy()
    change(directory)
    for read in (geometry_files.read_record, geometry_files.read_design, geometry_files.geometry_directory):
        with pytest.raises(InputError) as error:
            read(directory)
        message = str(error.value)
        assert named in message and says in message
        assert "\n" not in message
        assert f"delete {directory} and rerun snakemake" in message


@pytest.mark.parametrize("name", ["logarithmic_beta40", "circular_beta35", "logarithmic_beta35.5"])
def test_directory_named_for_another_design_point(copy, name):
    directory = copy(name)
    with pytest.raises(InputError, match=rf"{name}: holds the logarithmic design point at "
                                         r"spiral angle 35 deg, not the one its name says"):
        geometry_files.read_design(directory)


def test_directory_of_another_name_is_not_compared(copy):
    assert geometry_files.read_design(copy("paper_point")) == GearPairDesign()


def test_simulation_refuses_an_edited_directory(copy):
    """The dynamics read through lsbg.files: the 35 deg meshes are never simulated as 40 deg."""
    from lsbg.dynamics import load_model

    directory = copy()
    _spiral_40(directory)
    with pytest.raises(InputError, match="design.json: changed"):
        load_model(directory)


def test_not_a_geometry_directory(tmp_path):
    with pytest.raises(InputFileNotFoundError, match="nope: no such geometry directory"):
        geometry_files.read_record(tmp_path / "nope")
    with pytest.raises(FileNotFoundError):              # still a FileNotFoundError
        geometry_files.read_record(tmp_path / "nope")
    (tmp_path / "a.txt").write_text("x")
    with pytest.raises(InputError, match="a.txt: a file, not a geometry directory"):
        geometry_files.read_record(tmp_path / "a.txt")
    (tmp_path / "empty").mkdir()
    with pytest.raises(InputError, match="empty: an empty directory"):
        geometry_files.read_record(tmp_path / "empty")


# ------------------------------------------------------------------ NetCDF
@pytest.fixture
def netcdf(tmp_path):
    """A small dataset written by lsbg.files.write_dataset, and its values."""
    values = np.linspace(1.0, 2.0, 4000)
    ds = xr.Dataset({"force": ("time", values, {"units": "N", "long_name": "force"})},
                    coords={"time": ("time", np.arange(values.size) * 1e-3,
                                     {"units": "s", "long_name": "time"})},
                    attrs={"kind": "test"})
    path = tmp_path / "data.nc"
    write_dataset(ds, path)
    return path, values


def read(path):
    return open_dataset(path, "test", ("force",), ("kind",), "a test dataset")


def test_open_dataset_reads_what_was_written(netcdf):
    path, values = netcdf
    np.testing.assert_array_equal(read(path)["force"].values, values)


def test_written_variables_are_labelled_or_refused(tmp_path):
    """The writer completes a known label's units and long_name from its table and refuses
    a variable it cannot label, before writing anything."""
    ds = xr.Dataset({"force": ("member", [1.0, 2.0], {"units": "N", "long_name": "force"})},
                    coords={"member": ["pinion", "gear"]})
    write_dataset(ds, tmp_path / "ok.nc")
    with xr.open_dataset(tmp_path / "ok.nc") as back:
        assert back["member"].attrs["units"] == "1"
        assert back["member"].attrs["long_name"] == "gear member"
    bare = xr.Dataset({"stiffness": ("t", [1.0, 2.0], {"units": "N/m"})})
    with pytest.raises(ValueError, match=r"without units or long_name: stiffness \(give"):
        write_dataset(bare, tmp_path / "bare.nc")
    assert not (tmp_path / "bare.nc").exists()


def test_short_labels_cut_whole_words():
    """A label made from a long name keeps whole words: "...crowning um" never ends in
    "crowning u" (a unit's letter lost)."""
    name = "flank_modification.lengthwise_crowning_um"
    ds = xr.Dataset(coords={name: (name, [10.0], {"units": "um", "long_name": "x" * 50})})
    label = short_labels(ds)[name].attrs["long_name"]
    assert len(label) <= 40 and label == "flank modification.lengthwise crowning"
    assert ds[name].attrs["description"] == "x" * 50


@pytest.mark.parametrize("keep", [0, 8, 2000, 0.5, -1])
def test_truncated_netcdf_is_named(netcdf, keep):
    path, _ = netcdf
    data = path.read_bytes()
    path.write_bytes(data[:int(keep * len(data)) if isinstance(keep, float) else keep])
    with pytest.raises(InputError, match=rf"^{path}: not a readable NetCDF file, truncated or "
                                         r"corrupt \(.*\); delete it and rerun snakemake"):
        read(path)


def test_corrupt_values_fail_their_checksum(netcdf):
    """A flipped bit inside the data would otherwise be read back as a wrong number."""
    path, values = netcdf
    data = bytearray(path.read_bytes())
    at = bytes(data).index(values[1000:1002].tobytes())
    data[at + 3] ^= 0x10
    path.write_bytes(bytes(data))
    with pytest.raises(InputError, match=rf"^{path}: not a readable NetCDF file"):
        read(path)


def test_netcdf_missing_directory_or_wrong_kind(netcdf, tmp_path):
    path, _ = netcdf
    with pytest.raises(InputFileNotFoundError, match="nope.nc: no such test file"):
        read(tmp_path / "nope.nc")
    with pytest.raises(InputError, match=f"{tmp_path}: a directory, not a test file"):
        read(tmp_path)
    with pytest.raises(InputError, match=r"not a run dataset of lsbg.dynamics.dataset \(missing \["):
        from lsbg.dynamics.dataset import open_run
        open_run(path)
    (tmp_path / "text.nc").write_text("hello")
    with pytest.raises(InputError, match="text.nc: not a readable NetCDF file"):
        read(tmp_path / "text.nc")


# ------------------------------------------------------------- temporaries
def test_write_atomically_removes_a_dead_writers_temporaries(tmp_path):
    target = tmp_path / "run.nc"
    target.write_text("previous")
    stale = [tmp_path / ".run.nc.k3j_x9q1.part", tmp_path / ".run.nc.abcdefgh.part"]
    others = [tmp_path / ".run.nc.5.nc.abcdefgh.part",    # of the target run.nc.5.nc
              tmp_path / ".other.nc.abcdefgh.part", tmp_path / "run.nc.part"]
    for path in stale + others:
        path.write_text("left by kill -9")
    write_atomically(target, lambda tmp: open(tmp, "w").write("new"))
    assert target.read_text() == "new"
    assert not any(path.exists() for path in stale)
    assert all(path.exists() for path in others)


def test_a_failed_write_keeps_the_previous_file(tmp_path):
    target = tmp_path / "sweep.nc"
    target.write_text("previous")

    def broken(tmp):
        open(tmp, "w").write("half")
        raise RuntimeError("disk full")

    with pytest.raises(RuntimeError, match="disk full"):
        write_atomically(target, broken)
    assert target.read_text() == "previous"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["sweep.nc"]


def test_kill_during_write_then_rerun_leaves_no_part(tmp_path):
    """A writer really killed with SIGKILL in the middle of a write, then the next writer."""
    target = tmp_path / "run.nc"
    code = ("import sys, time\n"
            "from lsbg.files import write_atomically\n"
            "def slow(tmp):\n"
            "    open(tmp, 'w').write('half')\n"
            "    time.sleep(60)\n"
            "write_atomically(sys.argv[1], slow)\n")
    writer = subprocess.Popen([sys.executable, "-c", code, str(target)])
    try:
        deadline = time.monotonic() + 60
        while not list(tmp_path.glob(".run.nc.*.part")):
            assert writer.poll() is None and time.monotonic() < deadline
            time.sleep(0.05)
    finally:
        os.kill(writer.pid, signal.SIGKILL)
        writer.wait()
    assert list(tmp_path.glob(".run.nc.*.part")) and not target.exists()
    write_atomically(target, lambda tmp: open(tmp, "w").write("complete"))
    assert target.read_text() == "complete"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["run.nc"]


def test_write_geometry_removes_stale_temporary_directories(geometry, tmp_path):
    target = tmp_path / "logarithmic_beta35"
    stale = [tmp_path / ".logarithmic_beta35.a1b2c3d4.tmp",
             tmp_path / ".logarithmic_beta35.zz_99xyz.old"]
    for path in stale:
        shutil.copytree(geometry, path / "content")    # as big as a real one
    other = tmp_path / ".circular_beta35.a1b2c3d4.tmp"
    other.mkdir()
    write_geometry(GearPairDesign(), target)
    assert not any(path.exists() for path in stale)
    assert other.exists()
    assert geometry_files.read_design(target) == GearPairDesign()


def test_yaml_with_a_key_twice_is_refused_naming_both_lines(tmp_path):
    import yaml

    from lsbg.files import DuplicateKeyError, load_yaml

    for name in ("config.yaml", "config-test.yaml", "config-speed.yaml"):
        text = (Path(__file__).resolve().parents[1] / "workflow" / name).read_text()
        assert load_yaml(text) == yaml.safe_load(text)      # the same reader otherwise
    with pytest.raises(DuplicateKeyError, match=r"^c.yaml: line 5: key 'contact.slices' again "
                                                r"\(first at line 3\)"):
        load_yaml("simulation: {}\ncontact:\n  slices: 10\n  model: line\n  slices: 30\n",
                  "c.yaml")
    with pytest.raises(DuplicateKeyError, match=r"key 'sweeps.\[1\].mu' again"):
        load_yaml("sweeps:\n- {mu: 1}\n- mu: 1\n  mu: 2\n")
    # the same key in two mappings is no duplicate
    assert load_yaml("a: {x: 1}\nb: {x: 2}\n") == {"a": {"x": 1}, "b": {"x": 2}}
