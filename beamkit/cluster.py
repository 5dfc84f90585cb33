"""Where runs execute: a Dask client, on a local cluster or an existing one.

    with connect(scheduler=None, workers=None) as client: ...

scheduler: an address `tcp://HOST:PORT` or the file that `dask scheduler
--scheduler-file FILE` writes (else the environment's DASK_SCHEDULER_ADDRESS);
without one a local cluster with `workers` workers (default: the machine's
cores), each one thread in this process: a run is a solver process, so the
solves run side by side while the scene compiler's few milliseconds per run
take turns.  An unreachable scheduler raises BeamkitError within 2 x
CONNECT_TIMEOUT_S seconds (a TCP connection, then Dask's handshake), leaving
nothing running.
"""
import contextlib
import logging
import os
import sys
import time

from beamkit.api import BeamkitError

CONNECT_TIMEOUT_S = 5


def scheduler_address(scheduler=None):
    return scheduler or os.environ.get("DASK_SCHEDULER_ADDRESS") or None


@contextlib.contextmanager
def connect(scheduler=None, workers=None):
    """A distributed.Client for the runs (closed, and a local cluster shut down, on exit)."""
    addr = scheduler_address(scheduler)
    if workers is not None and (not isinstance(workers, int) or workers < 1):
        raise BeamkitError(f"error: --workers {workers}: expected a positive integer")
    try:
        from distributed import Client, LocalCluster
    except ImportError:
        raise BeamkitError("error: Dask is not installed: apt-get install python3-distributed "
                           "(./build.sh deps)") from None
    if addr:
        if "://" not in addr and os.path.isfile(addr):       # a file of dask scheduler --scheduler-file
            import json
            try:
                with open(addr, encoding="utf-8") as fh:
                    addr = json.load(fh)["address"]
            except (OSError, ValueError, KeyError, TypeError):
                raise BeamkitError(f"error: --scheduler {addr}: not a Dask scheduler file "
                                   f"(JSON with \"address\")") from None
        if "://" not in addr:
            raise BeamkitError(f"error: --scheduler {addr}: expected an address tcp://HOST:PORT "
                               f"or a scheduler file")
        _reachable(addr)
        try:
            client = Client(addr, timeout=f"{CONNECT_TIMEOUT_S}s", set_as_default=False)
        except (OSError, TimeoutError, ValueError) as e:
            raise BeamkitError(f"error: --scheduler {addr}: no Dask scheduler answered within "
                               f"{CONNECT_TIMEOUT_S} s ({str(e).splitlines()[0] if str(e) else type(e).__name__})"
                               ) from None
        try:
            yield client
        finally:
            client.close()
        return
    n = workers or os.cpu_count() or 1
    # (the scheduler's HTTP server, which Dask always starts, on a free local port)
    cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=False, dashboard_address="127.0.0.1:0",
                           silence_logs=logging.ERROR)
    client = Client(cluster, set_as_default=False)
    try:
        yield client
    finally:
        client.close()
        cluster.close()


def _reachable(addr):
    """A TCP connection to a tcp:// address, at most CONNECT_TIMEOUT_S: a refused or
    silent port is reported before Dask's client starts (and retries)."""
    import socket
    scheme, _, rest = addr.partition("://")
    if scheme != "tcp":
        return                             # tls://, ucx://, ...: Dask's client says
    host, _, port = rest.rpartition(":")
    host = host.strip("[]")
    try:
        port = int(port.split("/")[0])
    except ValueError:
        raise BeamkitError(f"error: --scheduler {addr}: expected an address tcp://HOST:PORT") from None
    try:
        with socket.create_connection((host, port), timeout=CONNECT_TIMEOUT_S):
            pass
    except OSError as e:
        why = "timed out" if isinstance(e, TimeoutError) else (e.strerror or str(e))
        raise BeamkitError(f"error: --scheduler {addr}: no Dask scheduler answered within "
                           f"{CONNECT_TIMEOUT_S} s ({why})") from None


class Progress:
    """runs done / total and time left on stderr: one line rewritten in place on a
    terminal, else a line at every tenth of the runs."""

    def __init__(self, total, label="runs", stream=None, enabled=True):
        self.total, self.label, self.done, self.failed = total, label, 0, 0
        self.stream = stream or sys.stderr
        self.enabled = enabled and total > 0
        self.tty = self.enabled and hasattr(self.stream, "isatty") and self.stream.isatty()
        self.t0 = time.monotonic()
        self._last_decile = -1

    def line(self):
        el = time.monotonic() - self.t0
        left = el / self.done * (self.total - self.done) if self.done else float("nan")
        width = 24
        fill = int(width * self.done / self.total) if self.total else width
        bar = "#" * fill + "." * (width - fill)
        fails = f", {self.failed} failed" if self.failed else ""
        left_s = "?" if left != left else _clock(left)
        return (f"[{bar}] {self.done}/{self.total} {self.label} done{fails}, "
                f"{_clock(el)} elapsed, {left_s} left")

    def update(self, failed=False):
        self.done += 1
        self.failed += bool(failed)
        if not self.enabled:
            return
        if self.tty:
            self.stream.write("\r" + self.line())
            if self.done == self.total:
                self.stream.write("\n")
            self.stream.flush()
        else:
            dec = 10 * self.done // self.total
            if dec != self._last_decile:
                self._last_decile = dec
                print(self.line(), file=self.stream, flush=True)


def _clock(s):
    s = int(round(s))
    return f"{s // 3600}:{s // 60 % 60:02d}:{s % 60:02d}" if s >= 3600 else f"{s // 60}:{s % 60:02d}"
