"""The engine-equivalence tests on NumPy's other dispatch path.

NumPy picks, at import, the widest SIMD code the CPU runs for many ufuncs
(``np.power`` among them: AVX-512 code that differs from the C library's
``pow`` in the last bit of some results). FastNSGA2 must give pymoo's
children, and so paper_nsga2's front, whichever code NumPy picked. The
suite runs on the CPU's own path; this module runs the equivalence tests of
``tests/test_fast_nsga2.py`` again in a subprocess with
``NPY_DISABLE_CPU_FEATURES`` naming every dispatch target above NumPy's
baseline that this CPU has, so a machine with AVX-512 and one without test
the same thing. On a CPU with nothing above the baseline the subprocess runs
the same tests on the one path there is (the test id says so).
"""

import os
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]

#: The engine-equivalence tests: operator twins against pymoo's operators,
#: FastNSGA2 against paper_nsga2 (every mode, the bundled scenario, every
#: encoding), and the checks below of the subprocess's own NumPy.
EQUIVALENCE = [
    "tests/test_fast_nsga2.py::test_sbx_twin_is_bit_identical",
    "tests/test_fast_nsga2.py::test_pm_twin_is_bit_identical",
    "tests/test_fast_nsga2.py::test_twins_are_bit_identical_on_real_valued_parents",
    "tests/test_fast_nsga2.py::test_fused_discrete_variation_is_bit_identical",
    "tests/test_fast_nsga2.py::test_modes_are_pymoos_nsga2_bit_for_bit",
    "tests/test_fast_nsga2.py::test_bundled_scenario_matches_paper_nsga2_and_generic_operators",
    "tests/test_fast_nsga2.py::test_every_encoding_is_pymoos_nsga2_bit_for_bit",
    "tests/test_simd_dispatch.py::test_numpy_runs_the_dispatch_path_it_was_given",
    "tests/test_simd_dispatch.py::test_numpy_power_of_an_element_ignores_its_array",
]


def _cpu():
    try:
        from numpy._core import _multiarray_umath as umath
    except ImportError:  # NumPy 1.x
        from numpy.core import _multiarray_umath as umath
    return umath.__cpu_baseline__, umath.__cpu_dispatch__, umath.__cpu_features__


def wide_simd_targets() -> list[str]:
    """NumPy's dispatch targets (above its baseline) that this CPU has, in
    NumPy's order, e.g. ``['X86_V3', 'X86_V4', 'AVX512_ICL', 'AVX512_SPR']``
    (also those this process was told to disable)."""
    _, dispatch, features = _cpu()
    return [f for f in dispatch if features.get(f) or f in _disabled()]


def _disabled() -> list[str]:
    return os.environ.get("NPY_DISABLE_CPU_FEATURES", "").replace(",", " ").split()


def test_numpy_runs_the_dispatch_path_it_was_given():
    """Every feature named in ``NPY_DISABLE_CPU_FEATURES`` is off in this
    NumPy; when no dispatch target runs (all disabled, or none on this CPU)
    and the baseline has no AVX-512, ``np.power`` is the C library's
    ``pow`` (``math.pow``), element by element."""
    import math

    baseline, dispatch, features = _cpu()
    for name in _disabled():
        assert name in dispatch and features.get(name) is False, f"NumPy still runs {name}"
    avx512_baseline = {"AVX512F", "AVX512_SKX", "X86_V4"} & set(baseline)
    if any(features.get(f) for f in dispatch) or avx512_baseline:
        return
    rng = np.random.default_rng(0)
    base = np.concatenate([1.0 + 30.0 * rng.random(500), 2.0 * rng.random(500)])
    for e in (-16.0, 1.0 / 16.0, 21.0, -3.5):
        libm = np.array([math.pow(x, e) for x in base])
        np.testing.assert_array_equal(np.power(base, np.full(len(base), e)), libm)


@pytest.mark.parametrize("exponent", [-16.0, -3.5, -1.0, 1.0 / 16.0, 0.5, 2.0, 21.0])
def test_numpy_power_of_an_element_ignores_its_array(exponent):
    """What the twins rely on (they power other arrays than pymoo does: both
    betas in one call, only the branch pymoo keeps): ``np.power`` of two
    float64 arrays gives an element the same result in an array of any
    length, at any position, in a strided view. (Not so with a scalar
    exponent: NumPy computes ``x ** 0.5``, ``x ** 2``, ``x ** -1`` then by
    ``sqrt``, ``x * x``, ``1 / x``; pymoo passes arrays, so do the twins.)"""
    rng = np.random.default_rng(1)
    base = np.concatenate([1.0 + 30.0 * rng.random(300), 2.0 * rng.random(300)])
    rng.shuffle(base)
    whole = np.power(base, np.full(len(base), exponent))
    for n in range(1, 41):
        for start in range(0, 60, 7):
            part = base[start : start + n].copy()
            np.testing.assert_array_equal(np.power(part, np.full(n, exponent)), whole[start : start + n])
    for step in (2, 3, 8):
        view = base[::step]
        np.testing.assert_array_equal(np.power(view, np.full(len(view), exponent)), whole[::step])


def _variant():
    """``(NPY_DISABLE_CPU_FEATURES of the subprocess or None, test id)``:
    the path this process does not run."""
    if _disabled():
        return None, "cpu-default-path-this-run-is-without-" + "-".join(_disabled())
    targets = wide_simd_targets()
    if targets:
        return " ".join(targets), "without-" + "-".join(targets)
    return None, "plain-cpu-has-no-simd-target-to-disable"


_DISABLE, _ID = _variant()


@pytest.mark.parametrize("disable", [_DISABLE], ids=[_ID])
def test_equivalence_tests_pass_on_the_other_dispatch_path(disable, tmp_path):
    env = {k: v for k, v in os.environ.items() if k != "NPY_DISABLE_CPU_FEATURES"}
    if disable:
        env["NPY_DISABLE_CPU_FEATURES"] = disable
    env["PYTHONPATH"] = os.pathsep.join(p for p in (str(ROOT / "src"), env.get("PYTHONPATH")) if p)
    report = tmp_path / "report.xml"
    proc = subprocess.run(
        [
            sys.executable,
            "-m",
            "pytest",
            "-q",
            "-p",
            "no:cacheprovider",
            "-o",
            "addopts=",
            f"--junitxml={report}",
            *EQUIVALENCE,
        ],
        cwd=ROOT,
        env=env,
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert proc.returncode == 0, proc.stdout[-4000:] + proc.stderr[-2000:]
    suite = ET.parse(report).getroot()
    suite = suite if suite.tag == "testsuite" else suite.find("testsuite")
    counts = {k: int(suite.get(k)) for k in ("tests", "failures", "errors", "skipped")}
    assert counts["failures"] == counts["errors"] == counts["skipped"] == 0, counts
    ran = {c.get("name").split("[")[0] for c in suite.iter("testcase")}
    assert ran == {node.split("::")[1] for node in EQUIVALENCE}, ran
