"""Aggregate an experiment's stored runs into tables and plots.

:func:`report` reads a store directory (:mod:`gapath.experiments.store`)
and writes, into the same directory:

``summary.csv``
    one row per configuration (the runs that differ only by seed): success
    rate, medians and quartiles of the per-run indicators, full precision;
``summary.md``
    the same as a Markdown table (medians with ``[first, third]``
    quartiles), with the package versions;
``timing.csv``
    median and total optimisation seconds per configuration (kept apart:
    the other files depend on the results only, so a resumed or distributed
    experiment writes them bit for bit like an uninterrupted local one);
``fronts/<config>.csv``
    the merged front (:func:`gapath.experiments.merge_fronts`) of each
    configuration whose map does not change with the seed;
``fronts.png``, ``indicators.png``
    the merged fronts, one panel per map, and box plots of the main
    indicator per configuration.

Quartiles are NumPy's default (linear) percentiles 25 and 75. Success means
that a run ends with at least one feasible path; ``min_length`` is the
length of the shortest feasible path of a successful run; generation counts
are pymoo's (1 = the initial population).
"""

from __future__ import annotations

import csv
import io
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from gapath.experiments.multirun import merge_fronts
from gapath.experiments.runner import front_from_dict
from gapath.experiments.spec import config_key, map_label, run_key
from gapath.experiments.store import ResultStore
from gapath.results import atomic_write, front_csv

__all__ = ["Report", "aggregate", "configuration_rows", "format_number", "report"]

#: Indicators summarised by median and quartiles (when present in the runs).
QUARTILE_FIELDS = (
    "n_gen",
    "first_feasible_gen",
    "min_length",
    "front_size",
    "n_eval",
    "hv_ratio",
    "igd_plus",
)


@dataclass
class Report:
    """Tables of an experiment.

    Attributes
    ----------
    rows : one dict per configuration (keys: :attr:`columns`).
    columns : column names of :attr:`rows`, in order.
    csv, markdown : the summary table as text.
    fronts : short configuration key -> merged :class:`gapath.front.PathFront`.
    files : the files written.
    """

    rows: list
    columns: list
    csv: str
    markdown: str
    fronts: dict = field(default_factory=dict)
    files: list = field(default_factory=list)


def _value(result: dict, name: str):
    if name in ("n_gen", "n_eval"):
        return result.get(name)
    return result.get("indicators", {}).get(name)


def _quartiles(values):
    arr = np.asarray([v for v in values if v is not None], float)
    if len(arr) == 0:
        return None, None, None
    q1, med, q3 = np.percentile(arr, [25, 50, 75])
    return float(med), float(q1), float(q3)


def _fmt_setting(v) -> str:
    if isinstance(v, list):
        return ",".join(map(str, v))
    return "none" if v is None else str(v)


def configuration_rows(spec, results: list[dict], failed_keys=frozenset()) -> tuple[list, list, dict]:
    """Aggregate ``results`` per configuration of ``spec``.

    Parameters
    ----------
    spec : :class:`gapath.experiments.spec.ExperimentSpec`.
    results : finished run results (:func:`gapath.experiments.runner.run_one`).
    failed_keys : keys of the runs whose last attempt failed.

    Returns
    -------
    ``(rows, columns, fronts)``: one row dict per configuration in the
    spec's order, the column names, and the merged front of each
    configuration with a seed-independent map.
    """

    norm = spec.to_dict()
    axes = list(norm["grid"])
    by_config: dict[str, list] = {}
    for r in results:
        by_config.setdefault(r["config"], []).append(r)
    seeds = norm["seeds"]
    has = {
        name: any(_value(r, name) is not None for r in results if r.get("status") == "ok")
        for name in QUARTILE_FIELDS
    }
    has["first_feasible_gen"] = has["first_feasible_gen"] or any(
        norm["options"].get(k) for k in ("stop_at_first_feasible", "record_first_feasible")
    )
    rows, fronts = [], {}
    for conf in spec.configurations():
        ck = config_key(conf)
        runs = [r for r in by_config.get(ck, []) if r.get("status") == "ok"]
        n_failed = sum(run_key(dict(conf, seed=s)) in failed_keys for s in seeds)
        row = {
            "config": ck[:10],
            "map": map_label(conf["map"]),
            "encoding": conf["encoding"],
            "engine": conf["engine"],
        }
        for a in axes:
            row[a] = _fmt_setting(conf["settings"][a])
        success = [r for r in runs if r["indicators"]["feasible"]]
        row.update(
            runs=len(seeds),
            done=len(runs),
            failed=n_failed,
            success_pct=100.0 * len(success) / len(runs) if runs else None,
            obstacles_mean=float(np.mean([r["indicators"]["n_obstacles"] for r in runs])) if runs else None,
        )
        for name in QUARTILE_FIELDS:
            if not has[name]:
                continue
            pool = success if name in ("first_feasible_gen", "min_length") else runs
            med, q1, q3 = _quartiles(_value(r, name) for r in pool)
            if name == "min_length":
                lengths = [r["indicators"]["min_length"] for r in success]
                row["min_length_mean"] = float(np.mean(lengths)) if lengths else None
                row["min_length_best"] = float(np.min(lengths)) if lengths else None
                anyp = [_value(r, "min_length_population") for r in runs]
                if any(v is not None for v in anyp):
                    row["min_length_population_mean"] = float(np.mean([v for v in anyp if v is not None]))
            row.update({f"{name}_median": med, f"{name}_q1": q1, f"{name}_q3": q3})
        fixed_map = all(a.get("seed") != "run" for a in conf["map"].values())
        if fixed_map:
            row["merged_front_size"] = None
            if runs:
                merged = merge_fronts([front_from_dict(r["front"]) for r in runs])
                fronts[row["config"]] = merged
                row["merged_front_size"] = len(merged)
        rows.append(row)
    columns = []
    for row in rows:
        columns += [c for c in row if c not in columns]
    for row in rows:
        for c in columns:
            row.setdefault(c, None)
    return rows, columns, fronts


def _csv_text(rows, columns) -> str:
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(columns)
    for row in rows:
        w.writerow(
            [
                "" if row[c] is None else (repr(row[c]) if isinstance(row[c], float) else row[c])
                for c in columns
            ]
        )
    return buf.getvalue()


def format_number(v, digits: int = 4) -> str:
    """A number as the report tables print it: ``-`` for None, integral
    floats without a decimal point, others to ``digits`` significant digits.

    Examples
    --------
    >>> format_number(None), format_number(12.0), format_number(3.14159, 3)
    ('-', '12', '3.14')
    """
    if v is None:
        return "-"
    if isinstance(v, float) and v.is_integer() and abs(v) < 1e15:
        return str(int(v))
    return f"{v:.{digits}g}"


def _mq(row, name, digits=4) -> str:
    med = row.get(f"{name}_median")
    if med is None:
        return "-"
    return f"{format_number(med, digits)} [{format_number(row[f'{name}_q1'], digits)}, {format_number(row[f'{name}_q3'], digits)}]"


def markdown_table(header: list[str], body: list[list[str]]) -> str:
    """A GitHub Markdown table."""
    lines = ["| " + " | ".join(header) + " |", "|" + "|".join("---" for _ in header) + "|"]
    lines += ["| " + " | ".join(str(c) for c in r) + " |" for r in body]
    return "\n".join(lines) + "\n"


def _markdown(norm: dict, rows, columns, status: dict, versions: list[dict]) -> str:
    axes = list(norm["grid"])
    header = ["config", "map", "encoding", "engine", *axes, "runs (failed)", "success %"]
    present = {c.rsplit("_", 1)[0] for c in columns if c.endswith("_median")}
    labels = [
        ("n_gen", "generations"),
        ("first_feasible_gen", "first feasible gen."),
        ("min_length", "min length"),
        ("front_size", "front size"),
        ("hv_ratio", "hv ratio"),
        ("igd_plus", "IGD+"),
    ]
    labels = [(n, lab) for n, lab in labels if n in present]
    header += [lab for _, lab in labels]
    if "min_length_mean" in columns:
        header.append("mean min length")
    if "merged_front_size" in columns:
        header.append("merged front")
    body = []
    for row in rows:
        line = [
            row["config"],
            row["map"],
            row["encoding"],
            row["engine"],
            *[row[a] for a in axes],
            f"{row['done']}/{row['runs']} ({row['failed']})",
            format_number(row["success_pct"], 3),
        ]
        line += [_mq(row, n) for n, _ in labels]
        if "min_length_mean" in columns:
            line.append(format_number(row["min_length_mean"]))
        if "merged_front_size" in columns:
            line.append(format_number(row["merged_front_size"]))
        body.append(line)
    text = [f"# Experiment {norm['name']}", ""]
    if norm.get("description"):
        text += [norm["description"], ""]
    settings = ", ".join(f"{k}={_fmt_setting(v)}" for k, v in sorted(norm["settings"].items()))
    opts = ", ".join(f"{k}={v}" for k, v in sorted(norm["options"].items()) if v)
    text += [
        f"Runs: {status['done']} of {status['total']} done, {status['failed']} failed, "
        f"{status['pending']} pending. Seeds: {len(norm['seeds'])} per configuration.",
        f"Fixed settings: {settings or '(solve defaults)'}." + (f" Options: {opts}." if opts else ""),
        "",
        "Cells are medians [first, third quartile] over the runs (generations to the "
        "first feasible path and path lengths over the successful runs; generation 1 is "
        "the initial population).",
        "",
        markdown_table(header, body),
    ]
    if versions:
        v = versions[0]
        text.append(
            "Versions: "
            + ", ".join(f"{k} {v[k]}" for k in sorted(v))
            + "."
            + (f" ({len(versions)} different version sets among the runs.)" if len(versions) > 1 else "")
        )
    return "\n".join(text) + "\n"


def _timing_csv(spec, results) -> str:
    by_config: dict[str, list] = {}
    for r in results:
        by_config.setdefault(r["config"], []).append(r.get("runtime", {}).get("seconds"))
    rows = []
    for conf in spec.configurations():
        secs = [s for s in by_config.get(config_key(conf), []) if s is not None]
        rows.append(
            {
                "config": config_key(conf)[:10],
                "map": map_label(conf["map"]),
                "runs": len(secs),
                "seconds_median": float(np.median(secs)) if secs else None,
                "seconds_total": float(np.sum(secs)) if secs else None,
            }
        )
    return _csv_text(rows, ["config", "map", "runs", "seconds_median", "seconds_total"])


def _plot_fronts(spec, rows, fronts):
    import matplotlib.pyplot as plt

    groups: dict[str, list] = {}
    for row in rows:
        if row["config"] in fronts and len(fronts[row["config"]]):
            groups.setdefault(row["map"], []).append(row)
    if not groups:
        return None
    n = min(len(groups), 6)
    fig, axes = plt.subplots(1, n, figsize=(4.2 * n, 3.8), squeeze=False)
    for ax, (label, group) in zip(axes[0], list(groups.items())[:n]):
        for row in group:
            f = fronts[row["config"]]
            y = f.F[:, 1] if f.F.shape[1] > 1 else np.zeros(len(f.F))
            name = " ".join(str(row[c]) for c in ("encoding", "engine", *spec.to_dict()["grid"]))
            ax.plot(f.F[:, 0], y, ".-", ms=4, lw=0.8, label=name)
        f0 = fronts[group[0]["config"]]
        ax.set_xlabel(f0.objectives[0])
        ax.set_ylabel(f0.objectives[1] if len(f0.objectives) > 1 else "")
        ax.set_title(f"{label}: merged fronts", fontsize=9)
        ax.legend(fontsize=6)
    return axes[0][0]


def _plot_indicators(rows, results):
    import matplotlib.pyplot as plt

    for name, label in (  # noqa: B007 (label is used after the loop)
        ("first_feasible_gen", "generation of the first feasible path"),
        ("hv_ratio", "hypervolume ratio"),
        ("front_size", "front size"),
    ):
        data = {}
        for r in results:
            v = _value(r, name) if r.get("status") == "ok" else None
            if v is not None:
                data.setdefault(r["config"][:10], []).append(v)
        if data:
            break
    else:
        return None
    order = [row for row in rows if row["config"] in data][:60]
    fig, ax = plt.subplots(figsize=(max(5.0, 0.35 * len(order) + 2), 4.0))
    ax.boxplot([data[row["config"]] for row in order], showfliers=True)
    ax.set_xticks(range(1, len(order) + 1), [row["map"] for row in order], rotation=70, fontsize=6)
    ax.set_ylabel(label)
    ax.set_title(f"{label} per configuration", fontsize=9)
    return ax


def aggregate(store_dir) -> tuple[list, list, dict]:
    """``(rows, columns, fronts)`` of :func:`configuration_rows` for a store
    directory, without writing anything."""
    store = ResultStore(store_dir)
    spec = store.spec()
    return configuration_rows(spec, store.results(), store.failed_keys() - store.done_keys())


def report(store_dir, *, plots: bool = True) -> Report:
    """Write the experiment's tables (and plots) into its store directory.

    Parameters
    ----------
    store_dir : a directory written by
        :func:`gapath.experiments.runner.run_experiment`.
    plots : also write ``fronts.png`` and ``indicators.png``.

    Returns
    -------
    :class:`Report` (the tables, the merged fronts and the files written).

    Raises
    ------
    ConfigError
        If the directory holds no experiment.
    """

    store = ResultStore(store_dir)
    spec = store.spec()
    runs = spec.runs()
    results = store.results(runs)
    status = store.status(runs)
    rows, columns, fronts = configuration_rows(spec, results, store.failed_keys() - store.done_keys())
    versions = []
    for r in results:
        if r.get("versions") not in versions:
            versions.append(r.get("versions"))
    text_csv = _csv_text(rows, columns)
    text_md = _markdown(spec.to_dict(), rows, columns, status, versions)
    root = Path(store_dir)
    files = []

    def write(name, data):
        atomic_write(root / name, data)
        files.append(root / name)

    write("summary.csv", text_csv)
    write("summary.md", text_md)
    write("timing.csv", _timing_csv(spec, results))
    for short, front in fronts.items():
        write(f"fronts/{short}.csv", front_csv(front))
    if plots:
        from gapath.plotting import png_bytes

        for name, draw in (
            ("fronts.png", lambda: _plot_fronts(spec, rows, fronts)),
            ("indicators.png", lambda: _plot_indicators(rows, results)),
        ):
            ax = draw()
            if ax is not None:
                write(name, png_bytes(ax))
    return Report(rows, columns, text_csv, text_md, fronts, files)
