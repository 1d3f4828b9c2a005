"""Shared cases for the experiment-runner tests: a tiny spec and the stored
results of a store without their run-dependent parts (times, hosts)."""

from gapath.experiments.runner import stable_part
from gapath.experiments.spec import ExperimentSpec
from gapath.experiments.store import ResultStore


def small_spec(**kw):
    """Two maps x two population sizes x two seeds, a few generations."""
    args = dict(
        name="tiny",
        maps=["default", {"dense": {"n": 8, "p0": 0.4, "seed": "run"}}],
        engines=["paper"],
        settings={"pop_size": 12, "n_gen": 4, "seed_from": "none"},
        grid={"pop_size": [12, 16]},
        seeds=2,
        options={"record_first_feasible": True},
    )
    args.update(kw)
    return ExperimentSpec(**args)


def stored(out) -> dict:
    """``{run key: result}`` of the store ``out``, stable parts only."""
    store = ResultStore(out)
    return {k: stable_part(store.read(k)) for k in store.done_keys()}
