"""Ahmed & Deb's encoding comparison (2013, section 5.3, Fig. 3).

On the 32x32 scenario with 173 random obstacles, every encoding (integer,
mixed, binary, and the absolute scheme the seeds dropped) runs 10 times with
pop 500 x 500 generations; the runs' fronts are merged. Each merged front
and each run is judged by its hypervolume ratio (SPEC) against the exact
column-monotone front. Two protocols are reported, clearly apart:

* ``seeds``: all-random initial populations, as in the paper;
* ``seeded``: gapath's default, the first population seeded with the
  shortest, safest and weighted-sum monotone paths.

The paper found integer better than mixed and mixed better than binary.
"""

from __future__ import annotations

import csv
import io
import time
from pathlib import Path

import numpy as np

from gapath.constraints import HANDLINGS
from gapath.experiments.multirun import multirun
from gapath.generators import default_workspace
from gapath.metrics import coverage, hv_ratio
from gapath.planners.exact import monotone_front
from gapath.results import atomic_write, dumps

ENCODING_ORDER = ("integer", "mixed", "binary", "absolute")
PROTOCOLS = {"seeds": "none", "seeded": "weighted"}
#: Settings of ``--quick`` (tests, notebooks, smoke runs).
QUICK = dict(runs=2, pop_size=40, n_gen=15)


def run(
    workspace=None,
    *,
    runs=10,
    pop_size=500,
    n_gen=500,
    seed=1,
    encodings=ENCODING_ORDER,
    protocols=tuple(PROTOCOLS),
    progress=None,
    penalties=(1000.0,),
    binary_rates=("bits",),
    on_run=None,
) -> dict:
    """Run the comparison.

    Parameters
    ----------
    workspace : default the bundled scenario.
    runs, pop_size, n_gen, seed : runs per encoding (seeds ``seed`` to
        ``seed + runs - 1``), population, generations.
    encodings, protocols : which encodings and protocols (:data:`PROTOCOLS`).
    progress : called with each row when it is complete.
    penalties : the obstacle handlings, each a penalty per interfering cell
        (a number) or a name of :data:`gapath.constraints.HANDLINGS` such as
        ``"adaptive"`` or ``"adaptive-ramp"`` (an
        :class:`gapath.constraints.AdaptivePenalty` up to 1000); every
        protocol and encoding runs under each.
    binary_rates : the binary encoding's initial bit-flip rates, each
        ``"bits"`` (1 / number of bits) or ``"grid"`` (1 / n, Ahmed & Deb's);
        the binary encoding runs once per rate.
    on_run : called with ``(row_key, SolveResult)`` after every run, the key
        being ``(protocol, penalty, encoding, binary_rate)``.

    Returns
    -------
    dict with ``rows`` (one per protocol, penalty, encoding and binary rate:
    merged and per-run hypervolume ratios, share of exact points found,
    seconds), ``per_run`` (the same keys as ``on_run`` -> the per-run
    hypervolume ratios in seed order), ``fronts`` (merged objective
    matrices, by ``(protocol, encoding)`` for the first penalty and rate)
    and ``exact`` (the reference front).
    """

    ws = default_workspace() if workspace is None else workspace
    exact = monotone_front(ws, ("length", "vulnerability"))
    rows, fronts, per_runs = [], {}, {}
    variants = [
        (protocol, pen, enc, rate)
        for protocol in protocols
        for pen in penalties
        for enc in encodings
        for rate in (binary_rates if enc == "binary" else (None,))
    ]
    for protocol, pen, enc, rate in variants:
        t0 = time.perf_counter()
        key = (protocol, pen, enc, rate)
        m = multirun(
            ws,
            runs=runs,
            seed=seed,
            encoding=enc,
            pop_size=pop_size,
            n_gen=n_gen,
            seed_from=PROTOCOLS[protocol],
            on_run=None if on_run is None else (lambda r, key=key: on_run(key, r)),
            **_handling_kwargs(pen, rate),
        )
        per_run = np.array([hv_ratio(r.front.F, exact.F) for r in m.runs])
        per_runs[key] = per_run.tolist()
        q1, med, q3 = np.percentile(per_run, [25, 50, 75])
        rows.append(
            dict(
                protocol=protocol,
                penalty=pen,
                encoding=enc,
                binary_rate=rate,
                runs=runs,
                pop_size=pop_size,
                n_gen=n_gen,
                merged_hv_ratio=round(float(hv_ratio(m.front.F, exact.F)), 6),
                merged_exact_points_found=round(float(coverage(m.front.F, exact.F)), 4),
                merged_front_size=len(m.front),
                run_hv_median=round(float(med), 6),
                run_hv_q1=round(float(q1), 6),
                run_hv_q3=round(float(q3), 6),
                run_hv_min=round(float(per_run.min()), 6),
                run_hv_max=round(float(per_run.max()), 6),
                seconds=round(time.perf_counter() - t0, 2),
            )
        )
        fronts.setdefault((protocol, enc), m.front.F)
        if progress:
            progress(rows[-1])
    return {"rows": rows, "per_run": per_runs, "fronts": fronts, "exact": exact.F, "workspace": ws}


def _handling_kwargs(penalty, binary_rate) -> dict:
    """solve's keywords for a penalty (a number or ``"adaptive"``) and a
    binary bit-flip rate (None for other encodings)."""

    kw = (
        {"constraints": "adaptive", "penalty": 1000.0, "adaptive_penalty": HANDLINGS[penalty]}
        if penalty in HANDLINGS
        else {"penalty": float(penalty)}
    )
    if binary_rate is not None and binary_rate != "bits":
        kw["pm_prob_var"] = binary_rate
    return kw


#: The command that regenerates ``docs/results/encodings.md``.
COMMAND = (
    "gapath experiment encodings --protocols seeds --penalties 1000,0.3,adaptive "
    "--binary-rates bits,grid --out docs/results"
)


def _label(row_or_key) -> str:
    """``encoding`` or ``binary (1/n)`` for the binary encoding's rates."""
    enc, rate = (
        (row_or_key["encoding"], row_or_key.get("binary_rate"))
        if isinstance(row_or_key, dict)
        else row_or_key[2:]
    )
    return {"bits": "binary (1/bits)", "grid": "binary (1/n)"}.get(rate, enc) if enc == "binary" else enc


def _handling(pen) -> str:
    return pen if isinstance(pen, str) else f"penalty {float(pen):g}"


def pairwise_tests(per_run: dict) -> list[dict]:
    """Two-sided Mann-Whitney U tests between the per-run hypervolume
    ratios of every two encodings run under the same protocol and penalty.

    Parameters
    ----------
    per_run : ``{(protocol, penalty, encoding, binary_rate): [hv, ...]}``
        (:func:`run`'s ``per_run``).

    Returns
    -------
    list of dicts: ``protocol``, ``penalty``, ``a``, ``b`` (labels),
    ``median_a``, ``median_b``, ``n_a``, ``n_b``, ``U`` (of ``a``), ``p``
    (two-sided; 1.0 when the two samples are all one value) and ``p_holm``
    (Holm's step-down adjustment over the pairs of the same protocol and
    penalty).

    Examples
    --------
    >>> t = pairwise_tests({("seeds", 1000, "integer", None): [0.9, 0.8, 0.85],
    ...                     ("seeds", 1000, "mixed", None): [0.5, 0.55, 0.6]})
    >>> t[0]["a"], t[0]["b"], t[0]["U"], round(t[0]["p"], 3), round(t[0]["p_holm"], 3)
    ('integer', 'mixed', 9.0, 0.1, 0.1)
    """
    from scipy.stats import mannwhitneyu

    out = []
    groups = {}
    for key, hv in per_run.items():
        groups.setdefault(key[:2], []).append((key, np.asarray(hv, float)))
    for (protocol, pen), members in groups.items():
        first = len(out)
        for i, (ka, a) in enumerate(members):
            for kb, b in members[i + 1 :]:
                if np.ptp(np.concatenate([a, b])) == 0:
                    u, p = len(a) * len(b) / 2.0, 1.0
                else:
                    res = mannwhitneyu(a, b, alternative="two-sided")
                    u, p = float(res.statistic), float(res.pvalue)
                out.append(
                    dict(
                        protocol=protocol,
                        penalty=pen,
                        a=_label(ka),
                        b=_label(kb),
                        median_a=float(np.median(a)),
                        median_b=float(np.median(b)),
                        n_a=len(a),
                        n_b=len(b),
                        U=u,
                        p=p,
                    )
                )
        _holm(out[first:])
    return out


def _holm(tests) -> None:
    """Holm's step-down adjusted p-values (``p_holm``) of one family."""
    order = sorted(range(len(tests)), key=lambda i: tests[i]["p"])
    running = 0.0
    for rank, i in enumerate(order):
        running = max(running, min(1.0, (len(tests) - rank) * tests[i]["p"]))
        tests[i]["p_holm"] = running


def _markdown(result) -> str:
    rows = result["rows"]
    ws = result["workspace"]
    lines = [
        "# Encoding comparison (Ahmed & Deb 2013, Fig. 3 set-up)",
        "",
        f"Regenerate: `{COMMAND}` (module `gapath.studies.encodings`).",
        "",
        f"Map: {ws.name} ({ws.shape[0]}x{ws.shape[1]}, {ws.n_obstacles} obstacles, start "
        "bottom-left, goal top-right; its generator kept a random monotone path free, which "
        "on this map is a 60-cell corridor along the bottom and right edges). "
        f"{rows[0]['runs']} runs x pop {rows[0]['pop_size']} x {rows[0]['n_gen']} generations per "
        "encoding and handling, GA seeds 1..runs, merged. Hypervolume ratio (SPEC: normalised by "
        "the exact front's ideal and nadir, reference point 1.1) against the exact "
        f"column-monotone front ({len(result['exact'])} points). `seeds` = all-random first "
        "population, as in the paper; `seeded` = gapath's default (shortest, safest and "
        "weighted-sum monotone paths in the first population). Handling: a fixed penalty per "
        "interfering cell added to both objectives (the paper gives no value; 1000 is "
        "gapath's default), or `adaptive` (`gapath.constraints.AdaptivePenalty`: from 1000, "
        "adapted to the share of feasible paths; see `penalty.md`). Binary encoding: initial "
        "bit-flip rate 1/bits (1/217 here, gapath's default) or 1/n (1/32, Ahmed & Deb's "
        '"mutation rate 1/n", n the grid size); the rate decays to a fifth over the run; '
        "the study's default is 1/bits (`--binary-rates bits`), `--binary-rates bits,grid` runs "
        "both. `seconds`: wall time of the row's runs (a shared machine, often loaded: "
        "indicative only).",
        *(
            []
            if any(r["protocol"] == "seeded" for r in rows)
            else [
                "",
                "Only the all-random protocol is run here; `--protocols seeded` adds gapath's "
                "seeded one (its last figures, at penalty 1000: BENCHMARKS.md, Encodings).",
            ]
        ),
        "",
        "| protocol | handling | encoding | merged HV ratio | exact points found | merged size | "
        "per-run HV median [q1, q3] | per-run min..max | seconds |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        lines.append(
            f"| {r['protocol']} | {_handling(r.get('penalty', 1000.0))} | {_label(r)} | "
            f"{r['merged_hv_ratio']:.4f} | "
            f"{r['merged_exact_points_found']:.0%} | {r['merged_front_size']} | "
            f"{r['run_hv_median']:.4f} [{r['run_hv_q1']:.4f}, {r['run_hv_q3']:.4f}] | "
            f"{r['run_hv_min']:.4f}..{r['run_hv_max']:.4f} | {r['seconds']} |"
        )
    tests = pairwise_tests(result.get("per_run", {}))
    lines += [
        "",
        "The paper (Fig. 3, no numbers published): the integer coding's merged front "
        "dominates the mixed coding's, which is better than the binary coding's.",
        "",
        "## Per-run differences between encodings",
        "",
        f"Two-sided Mann-Whitney U tests on the per-run hypervolume ratios ({rows[0]['runs']} "
        "runs each; p = 1 when both samples are one value), with Holm's adjustment over the "
        "pairs of each protocol and handling. A difference is called significant when the "
        "adjusted p is below 0.05.",
        "",
        "| protocol | handling | a | b | median a | median b | U | p | p (Holm) |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for t in tests:
        lines.append(
            f"| {t['protocol']} | {_handling(t['penalty'])} | {t['a']} | {t['b']} | "
            f"{t['median_a']:.4f} | {t['median_b']:.4f} | {t['U']:g} | {t['p']:.3g} | "
            f"{t['p_holm']:.3g} |"
        )
    lines.append("")
    for protocol, pen in dict.fromkeys((r["protocol"], r.get("penalty", 1000.0)) for r in rows):
        group = [r for r in rows if r["protocol"] == protocol and r.get("penalty", 1000.0) == pen]
        ranked = sorted(group, key=lambda r: -r["run_hv_median"])
        order = " > ".join(f"{_label(r)} ({r['run_hv_median']:.4f})" for r in ranked)
        sig = [t for t in tests if t["protocol"] == protocol and t["penalty"] == pen and t["p_holm"] < 0.05]
        med = {_label(r): r["run_hv_median"] for r in group}
        paper = [med.get(k) for k in ("integer", "mixed", "binary (1/bits)")]
        if None not in paper:
            if max(paper) - min(paper) < 0.005:
                verdict = "integer, mixed and binary tie (medians within 0.005): not the paper's order"
            elif paper[0] > paper[1] > paper[2]:
                verdict = "the paper's order, integer > mixed > binary, appears in the medians"
            else:
                verdict = "not the paper's order (integer > mixed > binary)"
            order += f" -- {verdict}"
        lines.append(
            f"- `{protocol}`, {_handling(pen)}: by per-run median, {order}; "
            + (
                "significant pairs (Holm): "
                + ", ".join(f"{t['a']} vs {t['b']} (p = {t['p_holm']:.2g})" for t in sig)
                if sig
                else "no pair differs significantly"
            )
            + "."
        )
    return "\n".join(lines) + "\n"


def write_outputs(result, out_dir) -> list[Path]:
    """``encodings.md``, ``encodings.csv``, ``encodings.json`` and
    ``encodings.png`` (merged fronts beside the exact front)."""
    import matplotlib.pyplot as plt

    from gapath.plotting import png_bytes

    out = Path(out_dir)
    rows = result["rows"]
    buf = io.StringIO()
    w = csv.DictWriter(buf, fieldnames=list(rows[0]), lineterminator="\n")
    w.writeheader()
    w.writerows(rows)
    atomic_write(out / "encodings.csv", buf.getvalue())
    atomic_write(out / "encodings.md", _markdown(result))
    per_run = result.get("per_run", {})
    rows_json = [
        dict(r, run_hv=per_run.get((r["protocol"], r.get("penalty"), r["encoding"], r.get("binary_rate"))))
        for r in rows
    ]
    atomic_write(out / "encodings.json", dumps(rows_json, indent=1) + "\n")
    protocols = list(dict.fromkeys(r["protocol"] for r in rows))
    fig, axes = plt.subplots(1, len(protocols), figsize=(5.5 * len(protocols), 4.5), squeeze=False)
    for ax, protocol in zip(axes[0], protocols):
        E = result["exact"]
        ax.scatter(E[:, 0], E[:, 1], s=60, facecolors="none", edgecolors="0.5", label="exact")
        for (p, enc), F in result["fronts"].items():
            if p == protocol and len(F):
                ax.scatter(F[:, 0], F[:, 1], s=12, label=enc)
        ax.set_xlabel("length")
        ax.set_ylabel("vulnerability")
        ax.set_title(f"merged fronts ({protocol})")
        ax.legend(fontsize=8)
    atomic_write(out / "encodings.png", png_bytes(axes[0][0]))
    return [out / f"encodings.{ext}" for ext in ("md", "csv", "json", "png")]
