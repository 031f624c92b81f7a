#!/usr/bin/python3
"""SciPy reference for the studies module's tests (src/studies/stats_test.cc).

Usage: /usr/bin/python3 scipy_reference.py IN.json OUT.json

IN.json: {"cases": [{"fn": ..., ...}, ...], "analyses": [{"instrument": {...},
"csv": PATH, "drop": [...], "censor": bool}, ...]}. OUT.json: {"cases": [[numbers...]],
"analyses": [{...same fields as `strangebeta study analyze --format json`...}]}, NaN as null.

Everything here is an independent re-implementation on numpy/scipy of the
definitions in docs/studies.md; it shares no code with the C++ module.
Exit code 3 when scipy is missing (the test then skips with a message).
"""
import csv
import itertools
import json
import math
import sys
import warnings

try:
    import numpy as np
    import scipy
    from scipy import stats
except ImportError as e:  # pragma: no cover
    print(f"scipy_reference.py: {e}", file=sys.stderr)
    sys.exit(3)

warnings.simplefilter("ignore")


def clean(v):
    """JSON-safe: NaN -> None, +-inf -> "inf"/"-inf", numpy scalars -> float/int."""
    if isinstance(v, (list, tuple)):
        return [clean(x) for x in v]
    if isinstance(v, dict):
        return {k: clean(x) for k, x in v.items()}
    if isinstance(v, (bool, str)) or v is None:
        return v
    if isinstance(v, (int, np.integer)):
        return int(v)
    f = float(v)
    if math.isinf(f):
        return "inf" if f > 0 else "-inf"
    return f if math.isfinite(f) else None


def cronbach(rows):
    m = np.asarray(rows, dtype=float)
    if m.ndim != 2 or m.shape[0] < 2 or m.shape[1] < 2:
        return math.nan
    k = m.shape[1]
    total_var = m.sum(axis=1).var(ddof=1)
    if not total_var > 0:
        return math.nan
    return k / (k - 1) * (1 - m.var(axis=0, ddof=1).sum() / total_var)


def kendall_w(ranks):
    """W with tie correction from per-rater average ranks; also Friedman's chi2."""
    m = len(ranks)
    if m < 1 or len(ranks[0]) < 2:
        return [math.nan, math.nan, math.nan, math.nan, math.nan]
    n = len(ranks[0])
    r = np.array([stats.rankdata(row) for row in ranks], dtype=float)
    ties = 0.0
    for row in ranks:
        _, counts = np.unique(row, return_counts=True)
        ties += float((counts ** 3 - counts).sum())
    col = r.sum(axis=0)
    s = float(((col - m * (n + 1) / 2) ** 2).sum())
    denom = m * m * (n ** 3 - n) - m * ties
    if not denom > 0:
        return [math.nan, math.nan, math.nan, math.nan, math.nan]
    w = 12 * s / denom
    chi2 = m * (n - 1) * w
    p = stats.chi2.sf(chi2, n - 1)
    fchi, fp = math.nan, math.nan
    if n >= 3 and m >= 2:
        res = stats.friedmanchisquare(*[np.asarray(ranks, dtype=float)[:, i] for i in range(n)])
        fchi, fp = res.statistic, res.pvalue
    return [w, chi2, p, fchi, fp]


def mwu(x, y):
    if len(x) == 0 or len(y) == 0:
        return [math.nan, math.nan]
    res = stats.mannwhitneyu(x, y, alternative="two-sided")
    return [res.statistic, res.pvalue]


def welch(x, y):
    if len(x) < 2 or len(y) < 2:
        return [math.nan, math.nan]
    res = stats.ttest_ind(x, y, equal_var=False)
    return [res.statistic, res.pvalue]


def tau(x, y):
    if len(x) == 0:
        return [math.nan, math.nan]
    res = stats.kendalltau(x, y)
    return [res.statistic, res.pvalue]


def pearson(x, y):
    if len(x) < 2:
        return [math.nan, math.nan]
    res = stats.pearsonr(x, y)
    return [res[0], res[1]]


def median(v):
    return float(np.median(v)) if len(v) else math.nan


def percentile(v, q):
    return float(np.percentile(v, q)) if len(v) else math.nan


def run_case(c):
    fn = c["fn"]
    if fn == "mannwhitneyu":
        return mwu(c["x"], c["y"])
    if fn == "welch":
        return welch(c["x"], c["y"])
    if fn == "kendalltau":
        return tau(c["x"], c["y"])
    if fn == "pearsonr":
        return pearson(c["x"], c["y"])
    if fn == "kendall_w":
        return kendall_w(c["ranks"])
    if fn == "cronbach":
        return [cronbach(c["rows"])]
    if fn == "rankdata":
        return list(stats.rankdata(c["x"]))
    if fn == "quantiles":
        return [median(c["x"]), percentile(c["x"], 25), percentile(c["x"], 75)]
    if fn == "distributions":
        # [norm.sf(z), t.cdf(t, df), chi2.sf(x, df), betainc(a, b, x)]
        return [stats.norm.sf(c["z"]), scipy.special.stdtr(c["df"], c["t"]),
                stats.chi2.sf(c["x"], c["df"]), scipy.special.betainc(c["a"], c["b"], c["bx"])]
    raise ValueError(f"unknown fn {fn}")


def route_key(label):
    try:
        if len(label) <= 18:
            return (0, int(label), label)
    except ValueError:
        pass
    return (1, 0, label)


def analyse(spec):
    inst = spec["instrument"]
    lo, hi = inst["scale"]
    items = inst["items"]
    k = len(items)
    ids = [it["id"] for it in items]
    with open(spec["csv"], newline="", encoding="utf-8") as f:
        table = [r for r in csv.reader(f) if any(x.strip() for x in r)]
    header = [h.strip() for h in table[0]]
    col = {h: i for i, h in enumerate(header)}
    rows = []
    for r in table[1:]:
        r = [x.strip() for x in r]
        keyed = []
        for j, it in enumerate(items):
            v = r[col[it["id"]]]
            if v == "":
                keyed.append(None)
            else:
                x = int(v)
                keyed.append(lo + hi - x if it.get("negative", False) else x)
        opt = lambda name, conv: (conv(r[col[name]]) if name in col and r[col[name]] != "" else None)
        rows.append({"participant": r[0], "route": r[1], "keyed": keyed,
                     "rank": opt("rank", int), "order": opt("order", int),
                     "ability": opt("ability", float)})
    complete = [r for r in rows if all(v is not None for v in r["keyed"])]

    def alpha_of(keep):
        idx = [i for i in range(k) if keep[i]]
        if len(idx) < 2:
            return math.nan
        return cronbach([[r["keyed"][i] for i in idx] for r in complete])

    keep = [True] * k
    censoring = "none"
    if spec.get("drop"):
        censoring = "owner"
        for d in spec["drop"]:
            keep[ids.index(d)] = False
    elif spec.get("censor"):
        censoring = "rule"
        current = alpha_of(keep)
        while sum(keep) > 2 and not math.isnan(current):
            best, best_alpha = None, current
            for i in range(k):
                if not keep[i]:
                    continue
                trial = list(keep)
                trial[i] = False
                a = alpha_of(trial)
                if a > best_alpha:
                    best, best_alpha = i, a
            if best is None:
                break
            keep[best] = False
            current = best_alpha

    out = {"alpha": alpha_of([True] * k), "alpha_censored": alpha_of(keep),
           "censoring": censoring, "dropped": [ids[i] for i in range(k) if not keep[i]],
           "rows": len(rows), "participants": len({r["participant"] for r in rows}),
           "complete_responses": len(complete), "items": []}
    for i in range(k):
        xs, tot = [], []
        for r in rows:
            if r["keyed"][i] is None:
                continue
            xs.append(r["keyed"][i])
            tot.append(sum(v for v in r["keyed"] if v is not None))
        trial = [True] * k
        trial[i] = False
        t = tau(xs, tot)
        out["items"].append({"id": ids[i], "dropped": not keep[i], "answered": len(xs),
                             "mean": float(np.mean(xs)) if xs else math.nan,
                             "alpha_if_deleted": alpha_of(trial),
                             "tau_item_total": t[0], "tau_item_total_p": t[1]})
    mid = (lo + hi) / 2
    for r in rows:
        vals = [r["keyed"][i] for i in range(k) if keep[i] and r["keyed"][i] is not None]
        r["sum"] = float(sum(vals)) if vals else None
        r["pct"] = 100.0 * sum(v > mid for v in vals) / len(vals) if vals else None
    labels = sorted({r["route"] for r in rows}, key=route_key)
    by_route = {}
    out["routes"] = []
    for lab in labels:
        rr = [r for r in rows if r["route"] == lab and r["sum"] is not None]
        sums = [r["sum"] for r in rr]
        pcts = [r["pct"] for r in rr]
        ranks = [r["rank"] for r in rows if r["route"] == lab and r["rank"] is not None]
        by_route[lab] = (sums, pcts)
        out["routes"].append({
            "route": lab, "n": len(sums), "median_sum": median(sums),
            "mean_sum": float(np.mean(sums)) if sums else math.nan,
            "min_sum": percentile(sums, 0), "q1_sum": percentile(sums, 25),
            "q3_sum": percentile(sums, 75), "max_sum": percentile(sums, 100),
            "mean_percent_positive": float(np.mean(pcts)) if pcts else math.nan,
            "ranked": len(ranks), "median_rank": median(ranks)})
    ranks_of = {}
    for r in rows:
        if r["rank"] is not None:
            ranks_of.setdefault(r["participant"], {})[r["route"]] = r["rank"]

    def concordance(routes):
        m = [[d[x] for x in routes] for _, d in sorted(ranks_of.items())
             if all(x in d for x in routes)]
        w = kendall_w(m) if m else [math.nan] * 5
        return {"w": w[0], "p": w[2], "chi2": w[1], "df": len(routes) - 1,
                "participants": len(m), "friedman_chi2": w[3], "friedman_p": w[4]}

    out["pairs"] = []
    for a, b in itertools.combinations(labels, 2):
        u = mwu(by_route[a][0], by_route[b][0])
        t = welch(by_route[a][1], by_route[b][1])
        out["pairs"].append({"a": a, "b": b, "u": u[0], "wilcoxon_p": u[1],
                             "welch_t": t[0], "welch_p": t[1],
                             "kendall_w": concordance([a, b])})
    out["kendall_w"] = concordance(labels)
    out["correlations"] = []
    scored = [r for r in rows if r["sum"] is not None]
    for x in ("order", "ability"):
        if x in col:
            sel = [r for r in scored if r[x] is not None]
            xs = [r[x] for r in sel]
            t = tau(xs, [r["sum"] for r in sel])
            p = pearson(xs, [r["pct"] for r in sel])
            out["correlations"].append({"x": x, "y": "sum|percent_positive", "n": len(sel),
                                        "tau": t[0], "tau_p": t[1], "r": p[0], "r_p": p[1]})
    if "order" in col and "rank" in col:
        sel = [r for r in rows if r["order"] is not None and r["rank"] is not None]
        xs, ys = [r["order"] for r in sel], [r["rank"] for r in sel]
        t, p = tau(xs, ys), pearson(xs, ys)
        out["correlations"].append({"x": "order", "y": "rank", "n": len(sel),
                                    "tau": t[0], "tau_p": t[1], "r": p[0], "r_p": p[1]})
    return out


def main():
    with open(sys.argv[1], encoding="utf-8") as f:
        spec = json.load(f)
    out = {"scipy": scipy.__version__,
           "cases": [run_case(c) for c in spec.get("cases", [])],
           "analyses": [analyse(a) for a in spec.get("analyses", [])]}
    with open(sys.argv[2], "w", encoding="utf-8") as f:
        json.dump(clean(out), f)


if __name__ == "__main__":
    main()
