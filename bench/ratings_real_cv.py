#!/usr/bin/python3
"""Cross-validation of the zones model's parts and prior widths (issue 35; docs/grades.md,
"Real outcomes": "How the defaults were chosen").

Usage: /usr/bin/python3 bench/ratings_real_cv.py [ascents.csv] > table.md
(default ../shared/data/ifsc-boulder-2025-26/ascents.csv; Debian's python3-numpy/scipy;
minutes: each configuration is six L-BFGS fits.)

Only the rows with heldout = 0 choose: each configuration is scored by 5-fold cross-validation
inside them (fold = sha1("athlete:route:cv") mod 5), the criterion being the CV log-loss of the
top plus that of the flash (the predictive log-likelihood of a row's two outcomes); the held-out
figures (fit heldout = 0, score heldout = 1) are printed beside it for the record, never used to
choose. The configurations are the rounds of a coordinate search, in the order they were run
(structure, session offsets, prior widths, later tries); the defaults of
src/grades/ratings_session.h are the configuration with the lowest criterion of all.

The model is the one of src/grades/ratings_session.h written again on scipy (a sparse design
matrix, L-BFGS to a gradient of 1e-8): per row a first-try game s(k (a - d)) won by a flash and
a session game s(k (a - d) + b [+ e_r] [+ u_c]) won by a top; with "zone", a first-try zone game
and a session zone game at the zone's difficulty z_r, with "link" its prior centred on d_r -
delta (sd "sz"), else N(0, sd^2); "learn" w: the tries after the first as per-try games at
weight w; "sa"/"sd": the abilities' / difficulties' prior sd; "se"/"su": the per-boulder /
per-athlete session offsets' sd (absent: none); "bround": one session offset per round.
"""
import csv, sys, hashlib, itertools
import numpy as np
from scipy import optimize, sparse
from scipy.special import expit, log_expit
from scipy.stats import rankdata
K = np.log(3.0)

def auc(y, p):
    y = np.asarray(y); rk = rankdata(p); npos = y.sum(); nneg = len(y) - npos
    return (rk[y == 1].sum() - npos * (npos + 1) / 2) / (npos * nneg)
def logloss(y, p):
    p = np.clip(np.asarray(p), 1e-15, 1 - 1e-15); y = np.asarray(y)
    return -np.mean(y * np.log(p) + (1 - y) * np.log(1 - p))

def load(path="../shared/data/ifsc-boulder-2025-26/ascents.csv"):
    out = []
    for r in csv.DictReader(open(path)):
        t = r["top_tries"].strip(); zt = r["zone_tries"].strip()
        out.append(dict(c=r["athlete_id"], r=r["route_id"], top=r["top"] == "1", n=int(t) if t else None,
                        zone=r["zone"] == "1", zn=int(zt) if zt else None, rnd=r["round"], ev=r["event_id"],
                        held=r["heldout"] == "1"))
    return out

ROUNDS = {"Qualification": 0, "Semi-final": 1, "Final": 2}

def fit(train, o):
    """o: dict of options. sa, sd: prior sds; zone: use zone games; link: zone difficulty prior
    centred on d - delta with sd sz (else independent N(0, sd)); bround: per-round session offsets;
    learn w: later tries at weight w; ztries: zone first-try game."""
    sa, sdd = o.get("sa", 3.0), o.get("sd", 3.0)
    cl = sorted({t["c"] for t in train}); ro = sorted({t["r"] for t in train})
    ci = {c: i for i, c in enumerate(cl)}; ri = {r: i for i, r in enumerate(ro)}
    C, R = len(cl), len(ro)
    # params: a[C], d[R], z[R], b[3], bz[1], delta
    iA, iD, iZ, iB, iBZ, iDel = 0, C, C + R, C + 2 * R, C + 2 * R + 3, C + 2 * R + 4
    iE, iU = iDel + 1, iDel + 1 + R
    N = iU + C
    rows, cols, vals, y, w = [], [], [], [], []
    g = 0
    def game(terms, win, wt):
        nonlocal g
        for j, v in terms:
            rows.append(g); cols.append(j); vals.append(v)
        y.append(win); w.append(wt); g += 1
    for t in train:
        a, d, z = iA + ci[t["c"]], iD + ri[t["r"]], iZ + ri[t["r"]]
        bidx = iB + (ROUNDS[t["rnd"]] if o.get("bround") else 0)
        n = t["n"]
        if n == 0:
            pass
        else:
            flash = t["top"] and n == 1
            game([(a, K), (d, -K)], 1 if flash else 0, 1.0)
            game([(a, K), (d, -K), (bidx, 1.0)] + ([(iE + ri[t['r']], 1.0)] if 'se' in o else []) + ([(iU + ci[t['c']], 1.0)] if 'su' in o else []), 1 if t["top"] else 0, 1.0)
            lw = o.get("learn", 0)
            if lw and n and n > 1:
                if t["top"]:
                    game([(a, K), (d, -K)], 1, lw)
                    if n > 2: game([(a, K), (d, -K)], 0, lw * (n - 2))
                else:
                    game([(a, K), (d, -K)], 0, lw * (n - 1))
        if o.get("zone") and t["zn"] != 0 and not (t["zn"] is None and t["n"] is None and not t["zone"] and False):
            zw = o.get("zw", 1.0)
            if o.get("ztries", True) and t["zn"] is not None:
                game([(a, K), (z, -K)], 1 if (t["zone"] and t["zn"] == 1) else 0, zw)
            game([(a, K), (z, -K), (iBZ if o.get("bz") else bidx, 1.0)], 1 if t["zone"] else 0, zw)
    A = sparse.csr_matrix((vals, (rows, cols)), shape=(g, N))
    y = np.array(y, float); w = np.array(w, float)
    # priors as rows of P x - mu with precision lam
    pr, pc, pv, mu, lam = [], [], [], [], []
    k = 0
    def prior(terms, m, s):
        nonlocal k
        for j, v in terms:
            pr.append(k); pc.append(j); pv.append(v)
        mu.append(m); lam.append(1 / s ** 2); k += 1
    for i in range(C): prior([(iA + i, 1)], 0, sa)
    for i in range(R): prior([(iD + i, 1)], 0, sdd)
    for i in range(R):
        if o.get("link"): prior([(iZ + i, 1), (iD + i, -1), (iDel, 1)], 0, o.get("sz", 1.0))
        else: prior([(iZ + i, 1)], 0, sdd)
    for i in range(3): prior([(iB + i, 1)], 2.0, 2.0)
    prior([(iBZ, 1)], 2.0, 2.0)
    prior([(iDel, 1)], 0, 10.0)
    for i in range(R): prior([(iE + i, 1)], 0, o.get('se', 1e-4))
    for i in range(C): prior([(iU + i, 1)], 0, o.get('su', 1e-4))
    P = sparse.csr_matrix((pv, (pr, pc)), shape=(k, N)); mu = np.array(mu); lam = np.array(lam)
    def f(x):
        zz = A @ x
        v = -np.sum(w * (y * log_expit(zz) + (1 - y) * log_expit(-zz)))
        r = P @ x - mu
        v += 0.5 * np.sum(lam * r * r)
        gr = A.T @ (w * (expit(zz) - y)) + P.T @ (lam * r)
        return v, gr
    x0 = np.zeros(N); x0[iB:iB + 4] = 2.0
    x = optimize.minimize(f, x0, jac=True, method="L-BFGS-B", options={"maxiter": 20000, "gtol": 1e-8, "maxcor": 30}).x
    def predict(t):
        a = x[iA + ci[t["c"]]] if t["c"] in ci else 0.0
        if t["r"] in ri: d = x[iD + ri[t["r"]]]
        else: d = 0.0
        b = x[iB + (ROUNDS[t["rnd"]] if o.get("bround") else 0)]
        e = x[iE + ri[t['r']]] if t['r'] in ri else 0.0
        u = x[iU + ci[t['c']]] if t['c'] in ci else 0.0
        zz = K * (a - d)
        return expit(zz), expit(zz + b + e + u)
    return predict, x

def score(pred, test):
    pf, ps = zip(*(pred(t) for t in test))
    yt = [1 if t["top"] else 0 for t in test]; yf = [1 if (t["top"] and t["n"] == 1) else 0 for t in test]
    return auc(yt, ps), logloss(yt, ps), auc(yf, pf), logloss(yf, pf)

def splits(rows):
    held = ([t for t in rows if not t["held"]], [t for t in rows if t["held"]])
    tr = [t for t in rows if t["ev"] != "1478"]; seen = {t["c"] for t in tr}
    temp = (tr, [t for t in rows if t["ev"] == "1478" and t["c"] in seen])
    return held, temp

def cv(train, o, folds=5):
    """k-fold CV inside train: fold by sha1(athlete:route:cv) mod folds."""
    fid = [int(hashlib.sha1(f"{t['c']}:{t['r']}:cv".encode()).hexdigest(), 16) % folds for t in train]
    res = []
    for f in range(folds):
        tr = [t for t, i in zip(train, fid) if i != f]; te = [t for t, i in zip(train, fid) if i == f]
        p, _ = fit(tr, o); res.append(score(p, te))
    return np.mean(res, axis=0)


ROUNDS_OF_SEARCH = [
    # structure
    ("session", {}),
    ("session + zones", {"zone": 1}),
    ("session + zones linked (sz 1)", {"zone": 1, "link": 1}),
    ("session + zones linked + per-round b", {"zone": 1, "link": 1, "bround": 1}),
    # session offsets
    ("zones + offsets se 1, su 0.6", {"zone": 1, "link": 1, "se": 1., "su": .6}),
    ("zones + offsets se 0.5, su 0.6", {"zone": 1, "link": 1, "se": .5, "su": .6}),
    ("zones + offsets se 1, su 0.3", {"zone": 1, "link": 1, "se": 1., "su": .3}),
    ("zones + offsets se 2, su 0.6", {"zone": 1, "link": 1, "se": 2., "su": .6}),
    ("zones + offsets se 1, su 1", {"zone": 1, "link": 1, "se": 1., "su": 1.}),
    ("zones + offsets se 0.5, su 0.3", {"zone": 1, "link": 1, "se": .5, "su": .3}),
]
B = {"zone": 1, "link": 1, "se": 1., "su": .3}
for name, e in [("sa 2", {"sa": 2.}), ("sa 4", {"sa": 4.}), ("sd 2", {"sd": 2.}), ("sd 4", {"sd": 4.}),
                ("sz 0.5", {"sz": .5}), ("sz 2", {"sz": 2.}), ("learn 0.1", {"learn": .1})]:
    ROUNDS_OF_SEARCH.append(("se 1, su 0.3, " + name, dict(B, **e)))
B2 = dict(B, sa=2.)
for name, e in [("sa 1.5", {"sa": 1.5}), ("learn 0.1", {"learn": .1}), ("sd 4", {"sd": 4.}),
                ("se 1.5", {"se": 1.5}), ("su 0.6", {"su": .6}), ("learn 0.05", {"learn": .05}),
                ("learn 0.2", {"learn": .2}), ("sa 1.5, learn 0.1", {"sa": 1.5, "learn": .1}),
                ("learn 0.1, sd 4", {"learn": .1, "sd": 4.}), ("learn 0.3", {"learn": .3}),
                ("learn 0.2, sd 4", {"learn": .2, "sd": 4.})]:
    ROUNDS_OF_SEARCH.append(("se 1, su 0.3, sa 2, " + name, dict(B2, **e)))


def main():
    path = sys.argv[1] if len(sys.argv) > 1 else "../shared/data/ifsc-boulder-2025-26/ascents.csv"
    held, _ = splits(load(path))
    print("| configuration | CV top AUC | CV top log-loss | CV flash AUC | CV flash log-loss | criterion |"
          " held-out top AUC | top log-loss | flash AUC |")
    print("|---|---|---|---|---|---|---|---|---|")
    best = None
    for name, o in ROUNDS_OF_SEARCH:
        c = cv(held[0], o)
        p, _ = fit(held[0], o)
        s = score(p, held[1])
        crit = c[1] + c[3]
        if best is None or crit < best[1]:
            best = (name, crit)
        print(f"| {name} | {c[0]:.4f} | {c[1]:.4f} | {c[2]:.4f} | {c[3]:.4f} | {crit:.4f} |"
              f" {s[0]:.4f} | {s[1]:.4f} | {s[2]:.4f} |", flush=True)
    print(f"\nlowest criterion: {best[0]} ({best[1]:.4f})")


if __name__ == "__main__":
    main()
