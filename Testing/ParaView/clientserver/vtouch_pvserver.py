"""A parallel pvserver for the client/server tests (issue 19), started and stopped safely.

    with ParallelServer(ranks=2) as server:
        Connect("127.0.0.1", server.port)
        ...

Starts ``mpiexec -np N --oversubscribe pvserver --server-port=P`` on 127.0.0.1 with a free port P,
in its own process group, with the parent's OMPI_*/PMIX_* variables stripped (a pvserver started
from inside an MPI-aware pvpython otherwise never listens) and root allowed (CI runs as root). Every
wait has a time-out: the server must say it is waiting for a client within ``start_timeout_s``, and
on exit the whole process group gets SIGTERM, then SIGKILL after ``stop_timeout_s``, so no test
hangs and no port or process is left behind. The server's output is kept (``server.output()``)
for failure messages.
"""

import os
import signal
import socket
import subprocess
import threading
import time


def free_port():
    """A TCP port on 127.0.0.1 that nothing listens on now."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def port_is_free(port):
    """Nothing listens on 127.0.0.1:port (connections closed there may linger in TIME_WAIT; a new
    listener with SO_REUSEADDR, as pvserver's, can bind it again)."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        try:
            s.bind(("127.0.0.1", port))
            s.listen(1)
        except OSError:
            return False
        return True


class ServerError(RuntimeError):
    pass


class ParallelServer:
    def __init__(self, ranks=2, start_timeout_s=120.0, stop_timeout_s=20.0, extra_args=()):
        self.ranks = ranks
        self.start_timeout_s = start_timeout_s
        self.stop_timeout_s = stop_timeout_s
        self.extra_args = list(extra_args)
        self.port = None
        self.process = None
        self._lines = []
        self._ready = threading.Event()
        self._reader = None

    def output(self):
        return "".join(self._lines)

    def _read_output(self):
        for line in self.process.stdout:
            self._lines.append(line)
            if "Waiting for client" in line or "Accepting connection" in line:
                self._ready.set()
        self._ready.set()  # the server ended: wake the waiter, which then sees it has exited

    def start(self):
        env = {k: v for k, v in os.environ.items() if not k.startswith(("OMPI_", "PMIX_"))}
        env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
                   OMPI_MCA_btl_vader_single_copy_mechanism="none")
        self.port = free_port()
        command = ["mpiexec", "-np", str(self.ranks), "--oversubscribe", "pvserver",
                   "--server-port=%d" % self.port] + self.extra_args
        self.process = subprocess.Popen(command, env=env, stdin=subprocess.DEVNULL,
                                        stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                        text=True, start_new_session=True)
        self._reader = threading.Thread(target=self._read_output, daemon=True)
        self._reader.start()
        if not self._ready.wait(self.start_timeout_s) or self.process.poll() is not None:
            output = self.output()
            self.stop()
            raise ServerError("pvserver (%d ranks) did not start listening on port %d within "
                              "%.0f s:\n%s" % (self.ranks, self.port, self.start_timeout_s, output))
        return self

    def is_running(self):
        return self.process is not None and self.process.poll() is None

    def session_pids(self):
        """Every process of the server's session: mpiexec and its ranks (Open MPI puts each rank
        in a process group of its own, but they stay in the session mpiexec leads)."""
        if self.process is None:
            return []
        pids = []
        for entry in os.listdir("/proc"):
            if entry.isdigit() and int(entry) != os.getpid():
                try:
                    if os.getsid(int(entry)) == self.process.pid:
                        pids.append(int(entry))
                except OSError:
                    pass  # gone meanwhile
        return pids

    def kill(self):
        """Kills the server at once (a crash, for the fault tests): SIGKILL to mpiexec's group and
        to each rank by its id (the ranks have process groups of their own)."""
        ranks = self.session_pids()
        if self.is_running():
            os.killpg(self.process.pid, signal.SIGKILL)
        for pid in ranks:
            try:
                os.kill(pid, signal.SIGKILL)
            except OSError:
                pass

    def stop(self):
        if self.process is None:
            return None
        if self.process.poll() is None:
            try:
                self.process.wait(timeout=self.stop_timeout_s / 2)  # exits when the client leaves
            except subprocess.TimeoutExpired:
                try:
                    os.killpg(self.process.pid, signal.SIGTERM)
                    self.process.wait(timeout=self.stop_timeout_s / 2)
                except (ProcessLookupError, subprocess.TimeoutExpired):
                    try:
                        os.killpg(self.process.pid, signal.SIGKILL)
                    except ProcessLookupError:
                        pass
                    self.process.wait(timeout=5)
        if self._reader is not None:
            self._reader.join(timeout=5)
        return self.process.returncode

    def connect(self, plugin, remote_plugin=True):
        """Connects this pvpython to the started server and loads `plugin` on both sides (the
        same file; only in the client when `remote_plugin` is False)."""
        from paraview import simple
        simple.Connect("127.0.0.1", self.port)
        if remote_plugin:
            simple.LoadPlugin(plugin, remote=True)
        simple.LoadPlugin(plugin, remote=False)

    def __enter__(self):
        return self.start()

    def __exit__(self, *exc):
        self.stop()
        return False


def rank_processes(server):
    """{MPI rank: pid} of `server`'s pvserver processes (of its session, by the rank Open MPI
    gives each in OMPI_COMM_WORLD_RANK)."""
    ranks = {}
    for pid in server.session_pids():
        try:
            with open("/proc/%d/comm" % pid) as f:
                if f.read().strip() != "pvserver":
                    continue
            with open("/proc/%d/environ" % pid, "rb") as f:
                env = dict(item.split(b"=", 1) for item in f.read().split(b"\0") if b"=" in item)
            ranks[int(env.get(b"OMPI_COMM_WORLD_RANK", b"0"))] = pid
        except (OSError, ValueError):
            continue  # a process that ended meanwhile
    return ranks


def status_mib(pid, key):
    """A /proc/<pid>/status memory line in MiB (key "VmHWM": the peak resident set, "VmRSS")."""
    with open("/proc/%d/status" % pid) as f:
        for line in f:
            if line.startswith(key + ":"):
                return int(line.split()[1]) / 1024.0
    return float("nan")


def write_float_nrrd(path, image):
    """`image` (a vtkImageData of 1 mm voxels at the origin) as a raw little-endian float NRRD,
    which VesselTouch's reader reads in pieces."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    dims = image.GetDimensions()
    values = vtk_to_numpy(image.GetPointData().GetScalars()).astype("<f4")
    with open(path, "wb") as f:
        f.write(("NRRD0004\ntype: float\ndimension: 3\nsizes: %d %d %d\nspacings: 1 1 1\n"
                 "encoding: raw\nendian: little\n\n" % dims).encode())
        f.write(values.tobytes())


def wait_until(condition, timeout_s, step_s=0.1):
    """Polls ``condition`` until it is true or ``timeout_s`` passed; returns its last value."""
    end = time.monotonic() + timeout_s
    while True:
        value = condition()
        if value or time.monotonic() > end:
            return value
        time.sleep(step_s)


def run_connected(plugin, check, body, ranks=2, remote_plugin=True, pass_server=False):
    """The client/server tests' frame: starts a `ranks`-rank pvserver, connects pvpython to it,
    loads `plugin` on both sides (the same file; only in the client when `remote_plugin` is
    False) and checks the rank count, runs body() (body(server) with `pass_server`: the fault
    tests kill it), then
    disconnects and checks that the server exits and frees its port. Any exception is a failed
    check, reported with the server's output; the server is always ended."""
    from paraview import servermanager as sm
    from paraview import simple
    server = ParallelServer(ranks=ranks)
    try:
        server.start()
        port = server.port
        server.connect(plugin, remote_plugin)
        partitions = sm.ActiveConnection.GetNumberOfDataPartitions()
        check(partitions == ranks, "the server has %d ranks, not %d" % (partitions, ranks))
        body(server) if pass_server else body()
        simple.Disconnect()
        code = server.stop()
        check(code is not None, "the server did not exit after the client disconnected")
        check(wait_until(lambda: port_is_free(port), 10.0), "port %d is still taken" % port)
    except Exception as e:  # noqa: BLE001 - report the server's output with any failure
        check(False, "%s: %s" % (type(e).__name__, e))
        print("server output:\n" + server.output())
    finally:
        server.stop()
