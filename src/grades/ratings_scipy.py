#!/usr/bin/python3
"""SciPy reference for the ascent rating (src/grades/ratings_scipy_test.cc).

Usage: /usr/bin/python3 ratings_scipy.py IN.json OUT.json

IN.json: {"cases": [{"params": {"logit_per_unit", "climber_sd", "setter_sd",
"open_route_sd", "felt_sd"}, "climbers": C, "routes": R, "setter": [value or
null per route], "ticks": [[climber, route, "flash"|"send"|"attempt",
attempts or null, felt value or null], ...]}, ...]}
OUT.json: {"cases": [{"difficulty": [...], "difficulty_sd": [...],
"ability": [...], "ability_sd": [...], "prior_mean": m, "success": bool}]}

An independent re-implementation of the model of docs/grades.md ("Grades
from ascents") on numpy/scipy, sharing no code with the C++ module: every
tick is expanded into its games here (flash = 1 win; send after n tries =
n - 1 losses and a win, n empty = 2; attempt = n losses, n empty = 1), the
negative log posterior is minimised by scipy.optimize.minimize
(trust-exact, with its gradient and Hessian written out from the formula),
and the standard deviations are the square roots of the diagonal of the
inverse Hessian (numpy.linalg.inv).
Exit code 3 when scipy is missing (the test then skips with a message).
"""
import json
import sys

try:
    import numpy as np
    from scipy import optimize
    from scipy.special import expit, log_expit
except ImportError as e:  # pragma: no cover
    print(f"ratings_scipy.py: {e}", file=sys.stderr)
    sys.exit(3)


def games(outcome, attempts):
    if outcome == "flash":
        return 1, 0
    if outcome == "send":
        n = 2 if attempts is None else attempts
        return 1, n - 1
    return 0, (1 if attempts is None else attempts)


def fit(case):
    k = case["params"]
    s = k["logit_per_unit"]
    C, R = case["climbers"], case["routes"]
    setter = case["setter"]
    graded = [g for g in setter if g is not None]
    felt_all = [t[4] for t in case["ticks"] if t[4] is not None]
    if graded:
        m = float(np.mean(graded))
    elif felt_all:
        m = float(np.mean(felt_all))
    else:
        m = 0.0
    mu = np.array([m if g is None else g for g in setter], dtype=float)
    sd = np.array([k["open_route_sd"] if g is None else k["setter_sd"] for g in setter])
    # One row per game: climber index, route index, 1 for a climber's win.
    gc, gr, gw = [], [], []
    fr, fv = [], []
    for c, r, outcome, attempts, felt in case["ticks"]:
        w, l = games(outcome, attempts)
        gc += [c] * (w + l)
        gr += [r] * (w + l)
        gw += [1] * w + [0] * l
        if felt is not None:
            fr.append(r)
            fv.append(felt)
    gc, gr, gw = np.array(gc, dtype=int), np.array(gr, dtype=int), np.array(gw, dtype=float)
    fr, fv = np.array(fr, dtype=int), np.array(fv, dtype=float)
    pa = 1.0 / k["climber_sd"] ** 2
    pf = 1.0 / k["felt_sd"] ** 2
    n = C + R

    def f(x):
        a, d = x[:C], x[C:]
        z = s * (a[gc] - d[gr])
        nll = -np.sum(gw * log_expit(z) + (1 - gw) * log_expit(-z))
        nll += 0.5 * pa * np.sum((a - m) ** 2)
        nll += 0.5 * np.sum(((d - mu) / sd) ** 2)
        nll += 0.5 * pf * np.sum((fv - d[fr]) ** 2)
        return nll

    def grad(x):
        a, d = x[:C], x[C:]
        z = s * (a[gc] - d[gr])
        e = s * (expit(z) - gw)  # d nll / d a for each game
        g = np.zeros(n)
        np.add.at(g, gc, e)
        np.add.at(g, C + gr, -e)
        g[:C] += pa * (a - m)
        g[C:] += (d - mu) / sd ** 2
        np.add.at(g, C + fr, pf * (d[fr] - fv))
        return g

    def hess(x):
        a, d = x[:C], x[C:]
        p = expit(s * (a[gc] - d[gr]))
        w = s * s * p * (1 - p)
        H = np.zeros((n, n))
        np.add.at(H, (gc, gc), w)
        np.add.at(H, (C + gr, C + gr), w)
        np.add.at(H, (gc, C + gr), -w)
        np.add.at(H, (C + gr, gc), -w)
        H[np.arange(C), np.arange(C)] += pa
        H[C + np.arange(R), C + np.arange(R)] += 1 / sd ** 2
        np.add.at(H, (C + fr, C + fr), pf)
        return H

    x0 = np.concatenate([np.full(C, m), mu])
    res = optimize.minimize(f, x0, jac=grad, hess=hess, method="trust-exact",
                            options={"gtol": 1e-12, "maxiter": 1000})
    x = res.x
    cov = np.linalg.inv(hess(x))
    sds = np.sqrt(np.diag(cov))
    return {"difficulty": x[C:].tolist(), "difficulty_sd": sds[C:].tolist(),
            "ability": x[:C].tolist(), "ability_sd": sds[:C].tolist(), "prior_mean": m,
            "success": bool(np.max(np.abs(grad(x))) < 1e-8)}


def main():
    with open(sys.argv[1]) as fh:
        spec = json.load(fh)
    out = {"cases": [fit(c) for c in spec["cases"]]}
    with open(sys.argv[2], "w") as fh:
        json.dump(out, fh)


if __name__ == "__main__":
    main()
