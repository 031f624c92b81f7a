#!/usr/bin/python3
"""The alternatives of issue 35's "model of the session", compared on real outcomes.

Usage: /usr/bin/python3 bench/ratings_real_alternatives.py [ascents.csv]
(default ../shared/data/ifsc-boulder-2025-26/ascents.csv; Debian's python3-numpy/scipy)

Each alternative is the ascent model of docs/grades.md (k = ln 3 per V grade, abilities and
difficulties with N(0, 3^2) priors: no setter's grades here) with a different reading of a tick
as games, fitted by MAP (scipy L-BFGS) on the rows with heldout = 0 and scored on heldout = 1
(and the temporal split: 2025 -> Bern 2026, athletes seen in 2025):

- tries: every try a game (the gyms' model; p_send = 1 - (1 - p)^T, T the mean tries);
- tick: one game per tick (a top wins; p_flash = p_send);
- discount w: tries, the failures after the first weighted w (learning / trailing failures);
- session b: a first-try game and a session game at k (a - d) + b, b fixed;
- session+tries w: the session model plus the tries after the first at weight w;
- session+route sd: the session model with a per-boulder session offset ~ N(0, sd^2) (and a
  per-athlete one ~ N(0, 0.6^2)): boulders that are read-and-sent vs. projects.

The C++ fit (`strangebeta ratings eval-real`) implements tries and session (b estimated
jointly); this script is the record of the rest (docs/grades.md, "Real outcomes").
"""
import csv
import sys

import numpy as np
from scipy import optimize
from scipy.special import expit, log_expit
from scipy.stats import rankdata

K = np.log(3.0)
SD = 3.0


def auc(y, p):
    y = np.asarray(y)
    rk = rankdata(p)
    npos = y.sum()
    nneg = len(y) - npos
    return (rk[y == 1].sum() - npos * (npos + 1) / 2) / (npos * nneg)


def logloss(y, p):
    p = np.clip(p, 1e-15, 1 - 1e-15)
    y = np.asarray(y)
    return -np.mean(y * np.log(p) + (1 - y) * np.log(1 - p))


def games(tick, kind, b, w):
    """(win, weight, session?) games of one tick (top, n)."""
    top, n = tick
    flash = top and n == 1
    if kind == "tries":
        if top:
            return [(1, 1, 0)] + ([(0, (n or 2) - 1, 0)] if (n or 2) > 1 else [])
        return [(0, n if n is not None else 1, 0)]
    if kind == "tick":
        return [(1 if top else 0, 1, 0)]
    if kind == "discount":
        m = ((n or 2) - 1) if top else (n if n is not None else 1)
        out = [(1, 1, 0)] if top else []
        return out + ([(0, 1 + w * (m - 1), 0)] if m > 0 else [])
    # session kinds
    out = [(1 if flash else 0, 1, 0), (1 if top else 0, 1, 1)]
    if kind == "session+tries" and n and n > 1:
        out += [(1, w, 0)] + ([(0, w * (n - 2), 0)] if n > 2 else []) if top else [(0, w * (n - 1), 0)]
    return out


def fit(train, kind, b=2.0, w=1.0, route_sd=None, athlete_sd=0.6):
    cl = sorted({t[0] for t in train})
    ro = sorted({t[1] for t in train})
    ci = {c: i for i, c in enumerate(cl)}
    ri = {r: i for i, r in enumerate(ro)}
    C, R = len(cl), len(ro)
    G = []
    for c, r, top, n in train:
        for win, wt, ses in games((top, n), kind, b, w):
            G.append((ci[c], ri[r], win, wt, ses))
    G = np.array(G, dtype=float)
    gc, gr = G[:, 0].astype(int), G[:, 1].astype(int)
    gw, gwt, gs = G[:, 2], G[:, 3], G[:, 4]
    extra = route_sd is not None
    N = C + R + (R + C if extra else 0)

    def f(x):
        a, d = x[:C], x[C:C + R]
        z = K * (a[gc] - d[gr]) + gs * b
        if extra:
            e, u = x[C + R:C + 2 * R], x[C + 2 * R:]
            z = z + gs * K * (e[gr] + u[gc])
        v = -np.sum(gwt * (gw * log_expit(z) + (1 - gw) * log_expit(-z)))
        v += 0.5 * (np.sum(a ** 2) + np.sum(d ** 2)) / SD ** 2
        q = gwt * (expit(z) - gw) * K
        g = np.zeros(N)
        np.add.at(g, gc, q)
        np.add.at(g, C + gr, -q)
        g[:C] += a / SD ** 2
        g[C:C + R] += d / SD ** 2
        if extra:
            v += 0.5 * np.sum(e ** 2) / route_sd ** 2 + 0.5 * np.sum(u ** 2) / athlete_sd ** 2
            np.add.at(g, C + R + gr, gs * q)
            np.add.at(g, C + 2 * R + gc, gs * q)
            g[C + R:C + 2 * R] += e / route_sd ** 2
            g[C + 2 * R:] += u / athlete_sd ** 2
        return v, g

    x = optimize.minimize(f, np.zeros(N), jac=True, method="L-BFGS-B",
                          options={"maxiter": 10000, "gtol": 1e-9}).x
    tries = [t[3] for t in train if t[3] is not None]
    T = max(1.0, float(np.mean(tries)))

    def predict(c, r):
        a = x[ci[c]] if c in ci else 0.0
        d = x[C + ri[r]] if r in ri else 0.0
        z = K * (a - d)
        pf = expit(z)
        if kind == "tries" or kind == "discount":
            return pf, 1 - (1 - pf) ** T
        if kind == "tick":
            return pf, pf
        zs = z + b
        if extra:
            zs += K * ((x[C + R + ri[r]] if r in ri else 0.0) + (x[C + 2 * R + ci[c]] if c in ci else 0.0))
        return pf, expit(zs)

    return predict


def score(predict, test):
    pf, ps = zip(*(predict(c, r) for c, r, _, _ in test))
    yt = [1 if t[2] else 0 for t in test]
    yf = [1 if (t[2] and t[3] == 1) else 0 for t in test]
    return auc(yt, ps), logloss(yt, ps), auc(yf, pf)


def main():
    path = sys.argv[1] if len(sys.argv) > 1 else "../shared/data/ifsc-boulder-2025-26/ascents.csv"
    rows = list(csv.DictReader(open(path)))
    T = []
    for r in rows:
        t = r["top_tries"].strip()
        T.append((r["athlete_id"], r["route_id"], r["top"] == "1", int(t) if t else None))
    held = ([t for t, r in zip(T, rows) if r["heldout"] == "0"],
            [t for t, r in zip(T, rows) if r["heldout"] == "1"])
    tr = [t for t, r in zip(T, rows) if r["event_id"] != "1478"]
    seen = {t[0] for t in tr}
    temporal = (tr, [t for t, r in zip(T, rows) if r["event_id"] == "1478" and r["athlete_id"] in seen])
    alts = [("tries", {}), ("tick", {})]
    alts += [("discount", {"w": w}) for w in (0.5, 0.2, 0.0)]
    alts += [("session", {"b": b}) for b in (1.0, 2.0, 3.0)]
    alts += [("session+tries", {"b": 2.0, "w": w}) for w in (0.1, 0.25)]
    alts += [("session+route", {"b": 2.0, "route_sd": s}) for s in (0.5, 1.0, 2.0)]
    print("| alternative | held-out top AUC | top log-loss | flash AUC | temporal top AUC | log-loss | flash AUC |")
    print("|---|---|---|---|---|---|---|")
    for kind, kw in alts:
        fk = "session" if kind == "session+route" else kind
        a = score(fit(held[0], fk, **kw), held[1])
        t = score(fit(temporal[0], fk, **kw), temporal[1])
        label = kind + "".join(f" {k}={v}" for k, v in kw.items())
        print(f"| {label} | {a[0]:.4f} | {a[1]:.4f} | {a[2]:.4f} | {t[0]:.4f} | {t[1]:.4f} | {t[2]:.4f} |")


if __name__ == "__main__":
    main()
