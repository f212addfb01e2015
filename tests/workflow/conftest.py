"""The session's study: the test configuration run once with -j2 in a copy of the repository,
shared by every end-to-end test of the workflow (tests/workflow/)."""

import os

import pytest

from tests.workflow.helpers import TEST_CONFIG, copy_repository, snakemake


@pytest.fixture(scope="session")
def study(tmp_path_factory):
    """The tiny study run with -j2 in a copy of the repository: (directory, environment)."""
    root = copy_repository(tmp_path_factory.mktemp("study"))
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(
        [str(root), *filter(None, [os.environ.get("PYTHONPATH")])]))
    snakemake("-j2", "--configfile", TEST_CONFIG, cwd=root, env=env, check=True)
    return root, env
