"""The workflow's job server (lsbg.cli.job_server): a job it serves writes the same
file, prints the same lines and exits with the same code as the ``lsbg`` process it
stands for; a job whose environment differs, or with no server, runs by itself; a
cancelled command stops its job; the server goes with the process that started it."""

import os
import signal
import subprocess
import sys
import time

from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import lsbg
from lsbg.gear.design import GearPairDesign
from lsbg.solid.export import write_geometry
from lsbg.cli import job_server

#: A short line-model run (compiled engine): the job the server and a process of its
#: own both run.
RUN = ["simulate", "--engine", "compiled", "--set", "contact.model=line",
       "--set", "simulation.duration_s=0.02", "--set", "simulation.samples=10",
       "--set", "simulation.ramp_time_s=0.005", "--set", "simulation.full_rate_after_s=0.01"]
#: The ``lsbg`` command (its console script's code).
LSBG = "import sys; from lsbg.cli import main; sys.exit(main())"
#: The ``lsbg`` command's side alone: its last line says whether the server ran the
#: job, and the job's exit code.
PROBE = ("import sys; from lsbg.cli.job_server import run_on_server; "
         "code = run_on_server(sys.argv[1:]); print('served' if code is not None else "
         "'not served', code)")


#: How long a process that ends may take to be gone [s]: on a loaded machine (the whole
#: suite on two cores) a supervisor that had nothing left to do was seen to take 5 s
#: and more to leave the process table; one that never ends still fails.
PROCESS_END_S = 60

#: The lsbg under test first on the path of every process here (the server's and the
#: commands'), whatever folder they start in.
PYTHONPATH = os.pathsep.join([str(Path(lsbg.__file__).resolve().parents[1]),
                              *filter(None, [os.environ.get("PYTHONPATH")])])


def _environment(**changes):
    """This process's environment with the thread counts of a one-thread job."""
    environ = {**os.environ, **job_server.ONE_THREAD, "PYTHONPATH": PYTHONPATH, **changes}
    return {k: v for k, v in environ.items() if v is not None}


@pytest.fixture(scope="module")
def server(tmp_path_factory):
    """A server as the workflow starts it, ready; stopped at the end."""
    process = job_server.start(directory=tmp_path_factory.mktemp("socket"),
                               environ=_environment())
    path = job_server.wait_ready(process)
    yield process, path
    job_server.stop(process)
    assert process.poll() is not None and not os.path.exists(path)


@pytest.fixture(scope="module")
def geometry(tmp_path_factory):
    path = tmp_path_factory.mktemp("served") / "logarithmic_beta35"
    write_geometry(GearPairDesign(), path, step=False)
    return path


def _command(code, args, path, cwd, **changes):
    """``python -c code args`` in ``cwd``, the server named by ``path`` (or not: a path
    where none listens, OFF), the environment changed by ``changes``; ``code`` is
    :data:`LSBG` (the command as the workflow's shell runs it) or :data:`PROBE`."""
    environ = _environment(**{job_server.SERVER_ENV: path, **changes})
    return subprocess.run([sys.executable, "-c", code, *args], cwd=cwd, env=environ,
                          capture_output=True, text=True)


def test_a_served_job_writes_the_same_numbers_as_a_process_of_its_own(server, geometry):
    _, path = server
    folder = geometry.parent
    args = [*RUN, "--geometry", str(geometry)]
    served = _command(PROBE, [*args, "--out", "served.nc"], path, folder)
    assert served.returncode == 0, served.stderr
    assert served.stdout.splitlines()[-1] == "served 0", served.stdout
    # its own lines reach the command's standard output, into the same file
    assert "lsbg simulate: compiled engine, line model -> served.nc" in served.stdout
    alone = _command(LSBG, [*args, "--out", "alone.nc"], job_server.OFF, folder)
    assert alone.returncode == 0, alone.stderr
    with xr.open_dataset(folder / "served.nc") as a, xr.open_dataset(folder / "alone.nc") as b:
        assert set(a.data_vars) == set(b.data_vars) and a.sizes["time"] == 11
        for name in a.data_vars:
            np.testing.assert_array_equal(a[name].values, b[name].values, err_msg=name)
        # the same command in the provenance (after its time stamp)
        assert a.attrs["history"].split(" ", 1)[1].replace("served.nc", "X") == \
            b.attrs["history"].split(" ", 1)[1].replace("alone.nc", "X")


def test_a_served_job_keeps_the_exit_code_and_message_of_a_bad_input(server, geometry):
    _, path = server
    missing = geometry.parent / "missing"
    served = _command(PROBE, ["simulate", "--geometry", str(missing), "--out", "x.nc"],
                      path, geometry.parent)
    assert served.stdout.splitlines()[-1] == "served 2", served.stdout + served.stderr
    assert "missing" in served.stderr and "Traceback" not in served.stderr
    assert not (geometry.parent / "x.nc").exists()
    # argparse's usage error: exit code 2 from SystemExit in the served process
    usage = _command(PROBE, ["simulate", "--geometry", str(geometry), "--out", "x.nc",
                             "--no-such-option"], path, geometry.parent)
    assert usage.stdout.splitlines()[-1] == "served 2"
    assert "unrecognized arguments: --no-such-option" in usage.stderr


def test_a_job_in_another_environment_runs_by_itself(server, geometry):
    _, path = server
    # two threads (a job with threads: 2) or another package path: not the server's imports
    for changes in ({"OMP_NUM_THREADS": "2"}, {"PYTHONPATH": str(geometry.parent)},
                    {"NUMBA_CACHE_DIR": str(geometry.parent / "cache")}):
        refused = _command(PROBE, ["--version"], path, geometry.parent, **changes)
        assert refused.stdout.splitlines()[-1] == "not served None", (changes, refused.stdout)
    # no server behind the name, or the server turned off: the command runs the job itself
    for name in (str(geometry.parent / "no.sock"), job_server.OFF):
        alone = _command(LSBG, ["--version"], name, geometry.parent)
        assert alone.returncode == 0 and alone.stdout.startswith("lsbg ")


def test_a_cancelled_command_stops_its_job(server, geometry):
    _, path = server
    folder = geometry.parent
    long_run = ["simulate", "--engine", "pybullet", "--set", "simulation.duration_s=2",
                "--set", "simulation.samples=50", "--geometry", str(geometry),
                "--out", "cancelled.nc"]
    environ = _environment(**{job_server.SERVER_ENV: path})
    command = subprocess.Popen([sys.executable, "-c", LSBG, *long_run], cwd=folder,
                               env=environ, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    time.sleep(2)  # under way: the run takes about 10 s (2 million PyBullet steps)
    assert command.poll() is None
    jobs = _served_jobs(path)
    assert jobs, "the job did not run in a process forked from the server"
    command.send_signal(signal.SIGTERM)
    assert command.wait(timeout=30) == 128 + signal.SIGTERM
    deadline = time.monotonic() + PROCESS_END_S
    while any(_exists(pid) for pid in jobs) and time.monotonic() < deadline:
        time.sleep(0.1)
    assert not any(_exists(pid) for pid in jobs)
    assert not (folder / "cancelled.nc").exists()


def test_a_command_gone_before_its_request_is_whole_leaves_no_process(server):
    """A connection closed after part of the request's header: its supervisor ends (it
    neither waits nor spins on the closed socket)."""
    import socket

    _, path = server
    before = set(_children(path))
    connection = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    connection.connect(path)
    connection.sendall(b"ab")
    # the connection's supervisor, waiting for the rest of the header; closed only once it
    # runs (on a busy machine the server accepts late: closed at once, the supervisor could
    # start after the wait below had found none and seen the test pass too early)
    deadline = time.monotonic() + PROCESS_END_S
    while not set(_children(path)) - before and time.monotonic() < deadline:
        time.sleep(0.01)
    supervisor = set(_children(path)) - before
    assert len(supervisor) == 1, supervisor
    connection.close()
    deadline = time.monotonic() + PROCESS_END_S
    while any(_exists(pid) for pid in supervisor) and time.monotonic() < deadline:
        time.sleep(0.1)
    assert not any(_exists(pid) for pid in supervisor)
    assert not set(_children(path)) - before


def _children(path):
    """The server's children: the supervisors of the jobs under way."""
    server = {p[0] for p in _processes() if p[2] == f"-P -m lsbg.cli.job_server {path}"}
    return [pid for pid, parent, _ in _processes() if parent in server and _exists(pid)]


def _served_jobs(path):
    """The processes that run jobs: the server's grandchildren."""
    children = set(_children(path))
    return [pid for pid, parent, _ in _processes() if parent in children]


def _processes():
    rows = []
    for entry in os.listdir("/proc"):
        if entry.isdigit():
            try:
                with open(f"/proc/{entry}/stat") as stat:
                    parent = int(stat.read().rsplit(")", 1)[1].split()[1])
                with open(f"/proc/{entry}/cmdline", "rb") as cmdline:
                    words = cmdline.read().split(b"\0")
            except OSError:
                continue
            text = " ".join(w.decode(errors="replace") for w in words[1:5] if w)
            rows.append((int(entry), parent, text))
    return rows


def _exists(pid):
    """True for a process that runs (not a zombie); False once it is gone, also when it
    goes between the two looks."""
    try:
        os.kill(pid, 0)
        with open(f"/proc/{pid}/stat") as stat:
            return stat.read().rsplit(")", 1)[1].split()[0] != "Z"
    except (ProcessLookupError, FileNotFoundError):
        return False


def test_the_server_stops_when_the_process_that_started_it_is_gone(tmp_path):
    parent = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(60)"])
    server = job_server.start(parent.pid, tmp_path, environ=_environment())
    path = Path(job_server.wait_ready(server))
    assert server.poll() is None
    assert oct(path.stat().st_mode & 0o777) == oct(0o600)  # only its user connects
    parent.kill()
    parent.wait()
    assert server.wait(timeout=10) == 0
    assert not path.exists()


def test_without_pidfds_a_supervisor_polls_for_its_job(tmp_path, geometry):
    """Where the kernel has no pidfd (``os.pidfd_open`` missing or refused), the supervisor
    polls: the job's exit code still comes back."""
    path = tmp_path / "jobs.sock"
    code = ("import os, sys; del os.pidfd_open; from lsbg.cli.job_server import serve; "
            "serve(sys.argv[1], int(sys.argv[2]))")
    server = subprocess.Popen([sys.executable, "-c", code, str(path), str(os.getpid())],
                              env=_environment())
    try:
        deadline = time.monotonic() + 60
        while not path.exists() and time.monotonic() < deadline:
            time.sleep(0.1)
        bad = _command(PROBE, ["simulate", "--geometry", str(geometry.parent / "missing"),
                               "--out", "x.nc"], str(path), tmp_path)
        assert bad.stdout.splitlines()[-1] == "served 2", bad.stdout + bad.stderr
        good = _command(PROBE, ["--version"], str(path), tmp_path)
        assert good.stdout.splitlines() == [f"lsbg {lsbg.__version__}", "served 0"]
    finally:
        server.terminate()
        server.wait(timeout=10)


def _probe_notebook(folder):
    """A report notebook that says whether its kernel started with the reports' imports
    done (forked by the server) or not (a Python of its own)."""
    import nbformat

    notebook = nbformat.v4.new_notebook()
    notebook.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3",
                                       "language": "python"}
    parameters = nbformat.v4.new_code_cell("x = 1")
    parameters.metadata["tags"] = ["parameters"]
    probe = nbformat.v4.new_code_cell(
        'import sys\nprint("kernel:", "forked" if "lsbg.figures.mesh" in sys.modules '
        'else "fresh", x)')
    notebook.cells = [parameters, probe]
    folder.mkdir(exist_ok=True)
    nbformat.write(notebook, folder / "probe.ipynb")
    return folder


def test_a_served_report_runs_its_notebook_in_a_kernel_the_server_forks(server, tmp_path):
    _, path = server
    notebooks = _probe_notebook(tmp_path / "notebooks")
    args = ["report", "probe", "--notebook-dir", str(notebooks), "--param", "x=2"]
    served = _command(LSBG, [*args, "--out", "served.html"], path, tmp_path)
    assert served.returncode == 0, served.stderr
    alone = _command(LSBG, [*args, "--out", "alone.html"], job_server.OFF, tmp_path)
    assert alone.returncode == 0, alone.stderr
    forked, fresh = ((tmp_path / name).read_text() for name in ("served.html", "alone.html"))
    # the kernel came with the server's imports, and without a server it starts as before
    assert "kernel: forked 2" in forked and "kernel: fresh 2" in fresh
    assert forked.replace("forked", "fresh") == fresh


def test_the_command_a_server_serves_imports_only_its_client():
    """``lsbg`` hands a job to the server before it imports the command line's options,
    configuration or numpy (about 0.1 s at each of a study's jobs); they still come
    when it runs a job itself, and with them the user's-mistake errors."""
    code = ("import sys; from lsbg.cli import main; from lsbg.cli.job_server import "
            "run_on_server; print(sorted(m for m in sys.modules if m.split('.')[0] in "
            "('numpy', 'yaml', 'jsonschema') or m in ('lsbg.cli.options', 'lsbg.config', "
            "'lsbg.gear.design')))")
    light = subprocess.run([sys.executable, "-c", code], env=_environment(),
                           capture_output=True, text=True, check=True)
    assert light.stdout.strip() == "[]", light.stdout
    from lsbg.cli import USER_ERRORS, CommandError
    from lsbg.config import ConfigError

    assert CommandError in USER_ERRORS and ConfigError in USER_ERRORS
