"""A server that starts the study's ``lsbg`` jobs from one warm process.

Every job of the study is a new ``lsbg`` process, and each paid about 1.2 s
before its first line of work: importing numpy, scipy, xarray and numba
(0.75 s) and numba's first dispatch, which loads its lowering registries
(0.45 s), for jobs whose work is often one or two seconds (measured on the
2-core reference machine, docs/performance.md). The default study runs 66 such
jobs. Under a local ``snakemake`` run the workflow starts this server once
(``onstart``); it imports all that, then forks one process per job, which
starts where a new ``lsbg`` process would be after its imports.

* **What a job sees.** The forked process takes the job's command line, working
  directory, environment, umask and standard input, output and error (passed
  over the socket), runs :func:`lsbg.cli.main` with them and exits with its
  exit code, which the ``lsbg`` command it stands for exits with. A signal to
  that command (Snakemake cancelling the job) reaches the job's process; if the
  command goes away, the job is stopped.
* **Same numbers.** The forked process runs the same code on the same inputs:
  only the imports it did not repeat differ. The server serves a job only if
  everything that decided what it imported and how is the job's too: the Python
  executable, the lsbg package's place, ``PYTHONPATH``, the numba and thread-count
  variables (Snakemake sets ``OMP_NUM_THREADS`` and the like to the job's
  threads), the cache directories. Otherwise it refuses and the ``lsbg``
  command runs the job itself, as it does when no server answers (before the
  server is ready, under SLURM, outside the workflow).
* **Lifetime.** The server stops with the Snakemake process that started it
  (``onsuccess`` and ``onerror``, or when that process is gone), and listens on
  a socket only its user can open.

Only the workflow's ``onstart`` starts it (:func:`start`); ``lsbg`` looks for
it only when :data:`SERVER_ENV` names a socket.
"""

from __future__ import annotations

import json
import os
import select
import signal
import socket
import struct
import subprocess
import sys
import tempfile
import time
from pathlib import Path

__all__ = ["SERVER_ENV", "OFF", "FINGERPRINT", "start", "socket_path", "wait_ready", "stop",
           "forked_kernel_manager",
           "serve", "run_on_server"]

#: The environment variable that names the server's socket (set for the jobs).
SERVER_ENV = "LSBG_JOB_SERVER"
#: Its value that turns the server off (``LSBG_JOB_SERVER=0 snakemake -j2``).
OFF = "0"
#: Environment variables that decide what a process imports and how (one of them
#: different: the job runs in a process of its own); names ending in ``_`` are prefixes.
FINGERPRINT = ("PYTHONPATH", "PYTHONHASHSEED", "PYTHONHOME", "NUMBA_", "OMP_NUM_THREADS",
               "GOTO_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS",
               "VECLIB_MAXIMUM_THREADS", "NUMEXPR_NUM_THREADS", "XDG_CACHE_HOME", "HOME",
               "MPLCONFIGDIR", "MPLBACKEND")
#: The thread counts the server's imports see: those of a one-thread job.
ONE_THREAD = {name: "1" for name in FINGERPRINT if name.endswith("_THREADS")}
#: Modules most jobs import (the stages' packages and what they import).
PRELOAD = ("numpy", "scipy.integrate", "scipy.optimize", "scipy.sparse.linalg", "xarray",
           "netCDF4", "numba", "jsonschema", "PIL.Image", "skfem", "lsbg.cli", "lsbg.files",
           "lsbg.dynamics", "lsbg.dynamics.compiled_engine", "lsbg.contact.mesh",
           "lsbg.experiments.verification", "lsbg.experiments.sensitivity",
           "lsbg.tca.analysis", "lsbg.tca.loaded", "lsbg.tca.vh_map", "lsbg.tooth.analysis",
           "lsbg.tooth.load_range", "lsbg.tooth.segment", "lsbg.solid.export",
           "lsbg.optimise.run", "lsbg.optimise.search", "lsbg.practice.design", "lsbg.rating",
           "lsbg.stats", "lsbg.aggregate.combine",
           # the reports' notebook kernels (lsbg notebook-kernel) and what their notebooks import
           "ipykernel.kernelapp", "pandas", "lsbg.reports")
#: Packages whose every module the server imports too: the reports' figures and tables.
PRELOAD_PACKAGES = ("lsbg.figures", "lsbg.tables")
#: How often the server looks whether the Snakemake process that started it is gone [s].
PARENT_CHECK_S = 1.0
#: How often a job's supervisor looks whether the job ended, without a pidfd [s].
POLL_S = 0.01
_HEADER = struct.Struct("!I")


def _fingerprint(environ, executable, package):
    """What must be the same for a job to run in a process forked from the server."""
    keys = sorted(k for k in environ if any(k == name or (name.endswith("_") and
                                                          k.startswith(name))
                                            for name in FINGERPRINT))
    return {"executable": os.path.realpath(executable), "package": str(package),
            "environment": {k: environ[k] for k in keys}}


def _package():
    return Path(__file__).resolve().parents[1]


# ---------------------------------------------------------------- the workflow's side
def start(parent_pid=None, directory=None, environ=None):
    """Start a server for the jobs of a Snakemake run.

    Parameters
    ----------
    parent_pid : int, optional
        The process whose end stops the server (default: this one).
    directory : str, optional
        Where its socket goes (default: the temporary directory; a socket's path
        must be short).
    environ : dict, optional
        The environment the server imports in, and which the jobs it serves share
        (default: this process's), with the thread counts of a one-thread job.

    Returns
    -------
    subprocess.Popen or None
        The server, None if ``environ[SERVER_ENV]`` is :data:`OFF`. Its socket is
        :func:`socket_path`, which the jobs find in ``SERVER_ENV`` (the caller
        sets it); it is ready once it exists (:func:`wait_ready`), and until then
        ``lsbg`` runs the jobs itself.
    """
    environ = dict(os.environ if environ is None else environ)
    if environ.pop(SERVER_ENV, None) == OFF:
        return None
    parent_pid = os.getpid() if parent_pid is None else parent_pid
    path = Path(directory or tempfile.gettempdir()) / f"lsbg-jobs-{os.getuid()}-{parent_pid}.sock"
    path.unlink(missing_ok=True)
    # (-P: no folder of the run's first on the path, so the server imports lsbg as the
    # `lsbg` command does, not a folder named lsbg in the working directory)
    return subprocess.Popen(
        [sys.executable, "-P", "-m", "lsbg.cli.job_server", str(path), str(parent_pid)],
        env={**environ, **ONE_THREAD}, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL, start_new_session=True)


def socket_path(process):
    """The socket of a server :func:`start` started [path]."""
    return process.args[4]


def wait_ready(process, timeout=60.0):
    """Wait until a server :func:`start` started listens; return its socket's path.

    Parameters
    ----------
    process : subprocess.Popen
    timeout : float
        Seconds to wait at most [s].

    Raises
    ------
    RuntimeError
        If the server stops first, or is not ready within ``timeout``.
    """
    path, deadline = socket_path(process), time.monotonic() + timeout
    while not os.path.exists(path):
        if process.poll() is not None:
            raise RuntimeError(f"the job server stopped (exit code {process.returncode}) "
                               f"before it was ready")
        if time.monotonic() > deadline:
            raise RuntimeError(f"the job server was not ready within {timeout:g} s")
        time.sleep(0.05)
    return path


def stop(process):
    """Stop a server :func:`start` started (its socket removed); a ``SERVER_ENV`` that
    names it is removed from this process's environment."""
    if process is None:
        return
    path = socket_path(process)
    if os.environ.get(SERVER_ENV) == path:
        del os.environ[SERVER_ENV]
    if process.poll() is None:
        process.terminate()
        try:
            process.wait(timeout=5)
        except subprocess.TimeoutExpired:
            process.kill()
    Path(path).unlink(missing_ok=True)


# ---------------------------------------------------------------- the server
def _preload():
    """Import what the jobs import and load numba's registries (what a job's first
    kernel call would do)."""
    import importlib
    import pkgutil

    for name in PRELOAD:
        importlib.import_module(name)
    for package in PRELOAD_PACKAGES:
        for module in pkgutil.iter_modules(importlib.import_module(package).__path__):
            importlib.import_module(f"{package}.{module.name}")
    from numba.core.registry import cpu_target

    cpu_target.target_context.refresh()
    from lsbg.cli import command_parsers

    command_parsers()


def serve(path, parent_pid=None):
    """Serve jobs on the socket ``path`` until SIGTERM or until ``parent_pid`` is gone.

    Parameters
    ----------
    path : str
        The socket's path (made here, once the imports are done).
    parent_pid : int, optional
        The Snakemake process.
    """
    _preload()
    fingerprint = _fingerprint(os.environ, sys.executable, _package())
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(0))
    signal.signal(signal.SIGCHLD, signal.SIG_IGN)  # the supervisors reap themselves
    listener = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    umask = os.umask(0o177)  # only this user may connect
    try:
        listener.bind(str(path))
    finally:
        os.umask(umask)
    listener.listen(64)
    try:
        while parent_pid is None or _alive(parent_pid):
            ready, _, _ = select.select([listener], [], [], PARENT_CHECK_S)
            if not ready:
                continue
            connection, _ = listener.accept()
            if _peer_uid(connection) != os.getuid():
                connection.close()
                continue
            sys.stdout.flush()
            sys.stderr.flush()
            if os.fork() == 0:
                listener.close()
                signal.signal(signal.SIGCHLD, signal.SIG_DFL)
                signal.signal(signal.SIGTERM, signal.SIG_DFL)
                code = 1
                try:
                    _supervise(connection, fingerprint)
                    code = 0
                finally:
                    os._exit(code)
            connection.close()
    finally:
        listener.close()
        Path(path).unlink(missing_ok=True)


def _alive(pid):
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def _peer_uid(connection):
    _, uid, _ = struct.unpack("3i", connection.getsockopt(socket.SOL_SOCKET, socket.SO_PEERCRED,
                                                          struct.calcsize("3i")))
    return uid


def _receive(connection):
    """The job's request and its three standard streams' descriptors.

    Raises
    ------
    ConnectionError
        If the ``lsbg`` command closed its end before the whole request came.
    """
    data, fds, _, _ = socket.recv_fds(connection, 65536, 3)

    def at_least(size, data):
        while len(data) < size:
            chunk = connection.recv(65536)
            if not chunk:
                raise ConnectionError("the lsbg command went away")
            data += chunk
        return data

    data = at_least(_HEADER.size, data)
    size = _HEADER.unpack_from(data)[0]
    return json.loads(at_least(_HEADER.size + size, data)[_HEADER.size:]), fds


def _supervise(connection, fingerprint):
    """One job: fork the process that runs it, pass its exit status back; stop it if
    the ``lsbg`` command goes away."""
    request, fds = _receive(connection)
    mine = _fingerprint(request["environment"], request["executable"], request["package"])
    if len(fds) != 3 or mine != fingerprint:
        connection.sendall(b"refused\n")
        return
    worker = os.fork()
    if worker == 0:
        connection.close()
        _run_job(request, fds)
    for fd in fds:
        os.close(fd)
    try:
        connection.sendall(f"pid {worker}\n".encode())
        # the job's end wakes the wait (a pidfd; where there is none, a poll every 10 ms)
        try:
            done, poll = [os.pidfd_open(worker)], None
        except (AttributeError, OSError):
            done, poll = [], POLL_S
        while True:
            ready, _, _ = select.select(done + [connection], [], [], poll)
            ended, status = os.waitpid(worker, os.WNOHANG)
            if ended:
                connection.sendall(f"exit {os.waitstatus_to_exitcode(status)}\n".encode())
                return
            if connection in ready and not connection.recv(1):
                break  # the lsbg command is gone
    except OSError:
        pass  # the lsbg command is gone (its end of the socket closed)
    # ... and so is its job
    os.kill(worker, signal.SIGTERM)
    os.waitpid(worker, 0)


def _run_job(request, fds):
    """In the forked process: become the job, run it, exit with its code."""
    code = 1
    try:
        for target, fd in enumerate(fds):
            os.dup2(fd, target)
            os.close(fd)
        signal.signal(signal.SIGINT, signal.default_int_handler)
        os.chdir(request["cwd"])
        os.umask(request["umask"])
        os.environ.clear()
        os.environ.update(request["environment"])
        tempfile.tempdir = None  # from the job's TMPDIR
        sys.argv = ["lsbg", *request["argv"]]
        from lsbg.cli import main

        try:
            code = main(request["argv"])
        except SystemExit as exit_:  # as Python exits: a message is printed, exit code 1
            code = exit_.code
            if code is not None and not isinstance(code, int):
                print(code, file=sys.stderr)
                code = 1
        except BaseException:
            import traceback

            traceback.print_exc()
            code = 1
    finally:
        import logging

        logging.shutdown()
        for stream in (sys.stdout, sys.stderr):
            try:
                stream.flush()
            except Exception:
                pass
        os._exit(int(code or 0))


# ---------------------------------------------------------------- the reports' kernels
def forked_kernel_manager():
    """A notebook kernel manager whose kernel this process's job server forks, if one runs.

    A report's notebook kernel (ipykernel's ``python -m ipykernel_launcher -f FILE``) then
    starts as ``lsbg notebook-kernel --connection-file FILE`` in the same interpreter,
    which the server forks from a process that has imported what the notebooks import
    (:data:`PRELOAD`, :data:`PRELOAD_PACKAGES`): the same kernel and code, without a new
    Python importing ipykernel and the reports' modules (measured: 8.3 -> 7.2 s for the
    verification report, docs/performance.md). A kernel the server does not serve runs
    in a process of its own, as ``lsbg`` does.

    Returns
    -------
    type or None
        An :class:`jupyter_client.manager.AsyncKernelManager` subclass for
        :func:`lsbg.reports.render_report`, or None where no server is named.
    """
    if os.environ.get(SERVER_ENV, OFF) == OFF:
        return None
    from jupyter_client.manager import AsyncKernelManager

    class ForkedKernelManager(AsyncKernelManager):
        def format_kernel_cmd(self, extra_arguments=None):
            command = super().format_kernel_cmd(extra_arguments)
            # ipykernel's own kernel: python -m ipykernel_launcher -f FILE [OPTIONS]
            if command[1:4] != ["-m", "ipykernel_launcher", "-f"]:
                return command
            return [command[0], "-c", "import sys; from lsbg.cli import main; sys.exit(main())",
                    "notebook-kernel", "--connection-file", command[4],
                    *(f"--kernel-option={option}" for option in command[5:])]

    return ForkedKernelManager


# ---------------------------------------------------------------- the lsbg command's side
def run_on_server(argv):
    """Run ``lsbg argv`` on the server named by :data:`SERVER_ENV`, if one serves it.

    Parameters
    ----------
    argv : list of str
        The command line after ``lsbg``.

    Returns
    -------
    int or None
        The job's exit code (128 + the signal that ended it), or None: no server,
        or one that does not serve this job (the caller runs it itself).
    """
    path = os.environ.get(SERVER_ENV, OFF)
    if path == OFF:
        return None
    connection = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    try:
        connection.connect(path)
    except OSError:
        connection.close()
        return None
    with connection:
        umask = os.umask(0)
        os.umask(umask)
        request = json.dumps({"argv": list(argv), "cwd": os.getcwd(),
                              "environment": dict(os.environ), "umask": umask,
                              "executable": sys.executable,
                              "package": str(_package())}).encode()
        data = _HEADER.pack(len(request)) + request
        try:
            sent = socket.send_fds(connection, [data], [0, 1, 2])
            connection.sendall(data[sent:])
            replies = connection.makefile("rb")
            first = replies.readline().split()
        except OSError:  # (a standard stream closed, the server gone)
            return None
        if not first or first[0] != b"pid":
            return None
        worker = int(first[1])

        def forward(signum, _frame):
            try:
                os.kill(worker, signum)
            except ProcessLookupError:
                pass

        for signum in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP):
            signal.signal(signum, forward)
        last = replies.readline().split()
        if not last or last[0] != b"exit":
            return 1  # the supervisor died: a failure, not a success
        code = int(last[1])
        return 128 - code if code < 0 else code


if __name__ == "__main__":
    serve(sys.argv[1], int(sys.argv[2]) if len(sys.argv) > 2 else None)
