"""Reference side of tests/scipy_crosscheck.rs: scipy's results for the Rust statistics.

Usage: python3 scipy_crosscheck.py INPUT.json  (prints the results as JSON on stdout)

The Rust test writes the data sets; this script answers with what scipy (and numpy,
statsmodels when installed, and exact rational arithmetic for Fisher's test) computes
for them, so the comparison catches a shared misunderstanding of a formula, not only a
typo. Non-finite numbers travel as the strings "inf", "-inf" and "nan" both ways, since
JSON has none.
"""

import json
import math
import sys
from fractions import Fraction

import numpy as np
import scipy
from scipy import stats


def number(v):
    """Reads a JSON number or one of the strings "inf", "-inf", "nan"."""
    return float(v)


def out(v):
    """Writes a float as a JSON number, or a string when it is not finite."""
    v = float(v)
    if math.isnan(v):
        return "nan"
    if math.isinf(v):
        return "inf" if v > 0 else "-inf"
    return v


def summary(values):
    a = np.array([number(v) for v in values])
    with np.errstate(invalid="ignore"):
        std = float(np.std(a, ddof=1)) if a.size > 1 else 0.0
        return {
            "n": int(a.size),
            "mean": out(np.mean(a)),
            "median": out(np.median(a)),
            "std": out(std),
            "min": out(np.min(a)),
            "max": out(np.max(a)),
        }


def rank_sum(case):
    x = [number(v) for v in case["x"]]
    y = [number(v) for v in case["y"]]
    r = stats.mannwhitneyu(
        x, y, alternative="two-sided", method="asymptotic", use_continuity=True
    )
    e = stats.mannwhitneyu(x, y, alternative="two-sided", method="exact")
    return {"u": out(r.statistic), "p_value": out(r.pvalue), "p_exact": out(e.pvalue)}


def holm_formula(p):
    """Holm's step-down adjustment written out (used when statsmodels is absent)."""
    p = np.asarray(p, dtype=float)
    order = np.argsort(p, kind="stable")
    m = p.size
    raw = p[order] * np.arange(m, 0, -1)
    adjusted = np.minimum(np.maximum.accumulate(raw), 1.0)
    result = np.empty(m)
    result[order] = adjusted
    return result


def holm(p):
    p = [number(v) for v in p]
    try:
        from statsmodels.stats.multitest import multipletests
    except ImportError:
        return "formula", [out(v) for v in holm_formula(p)]
    return "statsmodels", [out(v) for v in multipletests(p, method="holm")[1]]


def fisher_exact_rational(a, b, c, d):
    """Two-sided Fisher p-value in exact arithmetic: tables no more likely than observed."""
    row1, row2, col1 = a + b, c + d, a + c
    lo, hi = max(0, col1 - row2), min(row1, col1)
    weights = {x: math.comb(row1, x) * math.comb(row2, col1 - x) for x in range(lo, hi + 1)}
    observed = weights[a]
    tail = sum(w for w in weights.values() if w <= observed)
    return float(Fraction(tail, sum(weights.values())))


def fisher(table):
    a, b, c, d = table
    p = stats.fisher_exact([[a, b], [c, d]], alternative="two-sided").pvalue
    return {"p_value": out(p), "exact": out(fisher_exact_rational(a, b, c, d))}


def friedman(blocks):
    rows = np.array([[number(v) for v in block] for block in blocks])
    with np.errstate(invalid="ignore", divide="ignore"):
        r = stats.friedmanchisquare(*rows.T)
    mean_ranks = stats.rankdata(rows, method="average", axis=1).mean(axis=0)
    return {
        "statistic": out(r.statistic),
        "p_value": out(r.pvalue),
        "mean_ranks": [out(v) for v in mean_ranks],
    }


def main():
    with open(sys.argv[1], encoding="utf-8") as f:
        data = json.load(f)
    holm_source = "formula"
    holm_results = []
    for p in data["holm"]:
        holm_source, adjusted = holm(p)
        holm_results.append(adjusted)
    result = {
        "versions": {"scipy": scipy.__version__, "numpy": np.__version__},
        "summary": [summary(v) for v in data["summary"]],
        "rank_sum": [rank_sum(c) for c in data["rank_sum"]],
        "holm": holm_results,
        "holm_source": holm_source,
        "fisher": [fisher(t) for t in data["fisher"]],
        "friedman": [friedman(b) for b in data["friedman"]],
    }
    json.dump(result, sys.stdout, allow_nan=False)
    print()


if __name__ == "__main__":
    main()
