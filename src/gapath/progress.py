"""A live progress bar for pymoo runs on grid path problems."""

from __future__ import annotations

import numpy as np
from pymoo.core.callback import Callback
from tqdm import tqdm  # the text bar (tqdm.auto warns in kernels without ipywidgets)

from gapath.operators._columns import column


def population_status(algorithm) -> dict:
    """Generation, feasible count, front size and best unpenalised value per
    objective of the algorithm's current population."""
    pop = algorithm.pop
    problem = algorithm.problem
    interfering = column(pop, "interfering")
    feasible = np.zeros(len(pop), bool) if interfering is None else interfering == 0
    status = {"gen": int(algorithm.n_gen), "feasible": int(feasible.sum())}
    rank = column(pop, "rank")
    status["front"] = int(((rank == 0) & feasible).sum()) if rank is not None else 0
    if feasible.any():
        F = column(pop, "F")[feasible]
        if getattr(problem, "constraints", None) == "penalty":
            F = F - problem.penalty * interfering[feasible][:, None]
        for name, v in zip(problem.objectives, F.min(axis=0)):
            status[name] = float(v)
    return status


class Callbacks(Callback):
    """Several pymoo callbacks called in turn, each in full (``notify`` and
    ``update``; pymoo's ``CallbackCollection`` only calls ``update``)."""

    def __init__(self, *callbacks: Callback):
        super().__init__()
        self.callbacks = callbacks

    def notify(self, algorithm):
        for cb in self.callbacks:
            cb(algorithm)


class ProgressBar(Callback):
    """tqdm bar over generations showing :func:`population_status`.

    Parameters
    ----------
    n_gen : total number of generations (the bar's length).
    disable : no output at all (still tracks the algorithm).
    """

    def __init__(self, n_gen: int, disable: bool = False, **tqdm_kwargs):
        super().__init__()
        self.n_gen = n_gen
        self.disable = disable
        self.tqdm_kwargs = dict(mininterval=0.25, unit="gen", dynamic_ncols=True, **tqdm_kwargs)
        self.bar = None
        self.last_gen = 0

    def notify(self, algorithm):
        self.last_gen = int(algorithm.n_gen)
        if self.disable:
            return
        if self.bar is None:
            self.bar = tqdm(total=self.n_gen, **self.tqdm_kwargs)
        s = population_status(algorithm)
        self.bar.set_postfix_str(
            f"feasible={s['feasible']} front={s['front']}"
            + "".join(f" {k}={v:.4g}" for k, v in s.items() if k not in ("gen", "feasible", "front")),
            refresh=False)
        self.bar.update(s["gen"] - self.bar.n)

    def close(self):
        if self.bar is not None:
            self.bar.close()
            self.bar = None
