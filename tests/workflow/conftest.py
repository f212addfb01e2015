"""The session's study: the test configuration run once with -j2 in a copy of the repository,
shared by every end-to-end test of the workflow (tests/workflow/)."""

import pytest

from tests.workflow.helpers import TEST_CONFIG, repository_with_env, snakemake


@pytest.fixture(scope="session")
def study(tmp_path_factory):
    """The tiny study run with -j2 in a copy of the repository: (directory, environment)."""
    root, env = repository_with_env(tmp_path_factory.mktemp("study"))
    snakemake("-j2", "--configfile", TEST_CONFIG, cwd=root, env=env, check=True)
    return root, env
