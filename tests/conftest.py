"""Shared fixtures: short real runs of three design points, both contact models, two engines."""

import pytest

from lsbg.aggregate.combine import combine_runs
from lsbg.contact import ContactParameters
from lsbg.gear.design import GearPairDesign
from lsbg.dynamics import SimulationSettings, simulate
from lsbg.solid.export import write_geometry
from lsbg.tca.loaded import ltca_for_geometry
from lsbg.files import write_dataset


#: The fixtures that hold the session's study (directly or, for the SLURM run, by
#: comparison): a test that asks for one runs on that study's worker.
STUDY_FIXTURES = {"study", "slurm_study"}
#: The session's FE compliance (:func:`coarse_compliance`): its tests in one group too, so
#: that it is computed once (about 8 s), not on both workers.
COMPLIANCE_FIXTURE = "coarse_compliance"


@pytest.hookimpl(tryfirst=True)  # before pytest-xdist reads the groups from the marks
def pytest_collection_modifyitems(config, items):
    """The tests of the session's study (tests/workflow/conftest.py) in one group (``-n 2
    --dist loadgroup``, the README's command): they share that study and run in order on
    one worker, the largest group and so the first, while the other takes every other
    test, including the workflow tests that run in a folder of their own. The tests of
    the session's FE compliance are a group of their own, and so is a module whose
    module fixture is costly (tests/test_reports.py): each is built once."""
    for item in items:
        fixtures = set(getattr(item, "fixturenames", ()))
        if STUDY_FIXTURES & fixtures:
            item.add_marker(pytest.mark.xdist_group("workflow"))
        elif COMPLIANCE_FIXTURE in fixtures:
            item.add_marker(pytest.mark.xdist_group(COMPLIANCE_FIXTURE))
    # The SLURM run first: it waits on the cluster while the session's study is made.
    items.sort(key=lambda item: not item.nodeid.startswith("tests/workflow/test_slurm.py"))


SHORT = SimulationSettings(duration=0.05, samples=25, ramp_time=0.01)
# 26 instants 0, 0.002, ..., 0.05 s: 20 samples after 0.01 s, 4 subgroups of 5.
WINDOWS = dict(steady_state_after=0.01, window=(0.01, 0.05), subgroup_size=5)


@pytest.fixture(scope="session")
def windows():
    """Statistics windows that fit :data:`SHORT` runs (keywords of summary_table)."""
    return dict(WINDOWS)


@pytest.fixture(scope="session")
def runs(tmp_path_factory):
    """Point model: LSBG at 35 and 30 deg, SBG at 35 deg (pybullet) and LSBG at 35 deg
    (scipy); line model: LSBG and SBG at 35 deg (pybullet); their loaded TCAs."""
    root = tmp_path_factory.mktemp("study")
    points = {"lsbg35": ("logarithmic", 35), "sbg35": ("circular", 35),
              "lsbg30": ("logarithmic", 30)}
    paths = {}
    line = ContactParameters(model="line")
    for name, (trace, spiral) in points.items():
        geometry = root / "geometry" / name
        write_geometry(GearPairDesign.from_config({"trace": trace, "spiral_angle_deg": spiral}),
                       geometry)
        paths[name] = root / "runs" / f"{name}_pybullet.nc"
        write_dataset(simulate(geometry, SHORT), paths[name])
        if spiral == 35:
            paths[f"{name}_line"] = root / "runs" / f"{name}_line_pybullet.nc"
            write_dataset(simulate(geometry, SHORT, line), paths[f"{name}_line"])
            paths[f"{name}_mesh"] = root / "mesh" / f"{name}.nc"
            write_dataset(ltca_for_geometry(geometry, 1964.99, phases=64), paths[f"{name}_mesh"])
    paths["lsbg35_scipy"] = root / "runs" / "lsbg35_scipy.nc"
    write_dataset(simulate(root / "geometry" / "lsbg35", SHORT.replace(engine="scipy")),
                  paths["lsbg35_scipy"])
    return paths


@pytest.fixture(scope="session")
def pybullet_runs(runs):
    return [runs["lsbg35"], runs["sbg35"], runs["lsbg30"]]


@pytest.fixture(scope="session")
def sweep(pybullet_runs):
    return combine_runs(pybullet_runs)


@pytest.fixture(scope="session")
def coarse_compliance():
    """The paper pair's (LSBG, 35 deg) FE compliance on the coarsest mesh FEMeshSettings
    accepts (three elements across the tooth) and a coarse rim: computed once for the
    tests of the FE loaded TCA, its load range and the load curves (about 8 s)."""
    from lsbg.gear.geometry import GearPair
    from lsbg.tooth.compliance import FEMeshSettings, tooth_compliance

    return tooth_compliance(GearPair(GearPairDesign()),
                            settings=FEMeshSettings(tooth_size=0.52, body_size=10.0))
