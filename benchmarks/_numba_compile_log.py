"""pytest plugin used by ``bench_compile.py``: logs every numba compilation.

For each compilation it records the dispatcher, the argument types and the
exclusive compile time (the time of nested compilations, of the kernels it
calls, is charged to them), and writes one JSON line per compilation to the
file named by ``GAPATH_COMPILE_LOG`` when the session ends.
"""

from __future__ import annotations

import json
import os
import time

from numba.core import event

_open: list[list[float]] = []
_log: list[dict] = []


class _Listener(event.Listener):
    def on_start(self, ev):
        _open.append([time.perf_counter(), 0.0])

    def on_end(self, ev):
        t0, nested = _open.pop()
        dt = time.perf_counter() - t0
        if _open:
            _open[-1][1] += dt
        func = getattr(ev.data.get("dispatcher"), "py_func", None)
        name = f"{getattr(func, '__module__', '')}.{getattr(func, '__qualname__', '?')}"
        _log.append({"kernel": name, "args": str(ev.data.get("args")), "s": dt - nested})


event.register("numba:compile", _Listener())


def pytest_sessionfinish(session, exitstatus):
    path = os.environ.get("GAPATH_COMPILE_LOG")
    if path:
        with open(path, "w") as f:
            for rec in _log:
                f.write(json.dumps(rec) + "\n")
