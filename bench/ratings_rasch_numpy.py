#!/usr/bin/python3
"""The plain logistic (Rasch) fit of a TICKS.csv in numpy/scipy: the baseline of
docs/BENCHMARKS.md ("Grades from ascents at scale"), run whole-process beside
`strangebeta ratings fit` on the same file.

Usage: /usr/bin/python3 bench/ratings_rasch_numpy.py TICKS.csv

Reads the ticks (csv module), reads them as games as the tries model does (a
flash 1 win; a send after n tries n - 1 losses and a win, empty n 2; an
attempt n losses, empty 1), sums them per climber-route pair (numpy.unique),
and fits P(win) = sigmoid(a - d) with an L2 penalty 0.1 on every a and d by
scipy's L-BFGS-B (gradient by numpy.bincount) to a gradient of 1e-6. Prints
the pairs, iterations and the time of each phase.
"""
import csv
import sys
import time

import numpy as np
from scipy import optimize
from scipy.special import expit, log_expit


def main():
    t0 = time.time()
    climbers, routes = {}, {}
    ci, ri, wins, losses = [], [], [], []
    with open(sys.argv[1], newline="") as fh:
        rd = csv.reader(fh)
        head = next(rd)
        c_col, r_col, o_col, n_col = (head.index(k) for k in ("climber", "route", "outcome", "attempts"))
        for row in rd:
            if len(row) != len(head):
                continue
            o, n = row[o_col], row[n_col]
            if o == "flash":
                w, l = 1, 0
            elif o == "send":
                w, l = 1, (int(n) if n else 2) - 1
            else:
                w, l = 0, (int(n) if n else 1)
            ci.append(climbers.setdefault(row[c_col], len(climbers)))
            ri.append(routes.setdefault(row[r_col], len(routes)))
            wins.append(w)
            losses.append(l)
    t1 = time.time()
    C, R = len(climbers), len(routes)
    key = np.asarray(ri, dtype=np.int64) * C + np.asarray(ci, dtype=np.int64)
    uk, inv = np.unique(key, return_inverse=True)
    W = np.bincount(inv, weights=np.asarray(wins, dtype=float))
    L = np.bincount(inv, weights=np.asarray(losses, dtype=float))
    pc, pr = uk % C, uk // C
    N = W + L
    lam = 0.1
    t2 = time.time()

    def f(x):
        a, d = x[:C], x[C:]
        z = a[pc] - d[pr]
        v = -np.sum(W * log_expit(z) + L * log_expit(-z)) + 0.5 * lam * np.dot(x, x)
        e = N * expit(z) - W
        g = np.concatenate([np.bincount(pc, weights=e, minlength=C),
                            -np.bincount(pr, weights=e, minlength=R)]) + lam * x
        return v, g

    res = optimize.minimize(f, np.zeros(C + R), jac=True, method="L-BFGS-B",
                            options={"maxiter": 10000, "gtol": 1e-6})
    t3 = time.time()
    print(f"{len(wins)} ticks, {len(uk)} pairs, {C} climbers, {R} routes; "
          f"read {t1 - t0:.1f} s, pairs {t2 - t1:.1f} s, fit {t3 - t2:.1f} s "
          f"({res.nit} iterations, gradient {np.max(np.abs(res.jac)):.1e})")


if __name__ == "__main__":
    main()
