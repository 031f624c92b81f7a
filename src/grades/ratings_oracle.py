"""What the SciPy references of the ascent rating share (ratings_scipy.py,
ratings_drift_scipy.py): numpy/scipy or exit code 3, a tick's games, a case's
priors and ticks read into arrays, the Newton polish and the IN.json ->
OUT.json main. Independent of the C++ module like the scripts themselves.
"""
import json
import os
import sys

try:
    import numpy as np
    from scipy import optimize  # noqa: F401 (re-exported to the scripts)
    from scipy.special import expit, log_expit  # noqa: F401
except ImportError as e:  # pragma: no cover
    print(f"{os.path.basename(sys.argv[0])}: {e}", file=sys.stderr)
    sys.exit(3)


def games(outcome, attempts):
    """A tick's (wins, losses): flash = 1 win; send after n tries = n - 1
    losses and a win (n empty = 2); attempt = n losses (n empty = 1)."""
    if outcome == "flash":
        return 1, 0
    if outcome == "send":
        n = 2 if attempts is None else attempts
        return 1, n - 1
    return 0, (1 if attempts is None else attempts)


def route_priors(case):
    """(m, mu, sd): the prior mean m (the setters' grades' mean, else the felt
    grades', else 0) and per route its prior's mean and sd (the setter's
    grade at setter_sd, else m at open_route_sd)."""
    k = case["params"]
    setter = case["setter"]
    graded = [g for g in setter if g is not None]
    felt_all = [t[4] for t in case["ticks"] if t[4] is not None]
    m = float(np.mean(graded)) if graded else (float(np.mean(felt_all)) if felt_all else 0.0)
    mu = np.array([m if g is None else g for g in setter], dtype=float)
    sd = np.array([k["open_route_sd"] if g is None else k["setter_sd"] for g in setter])
    return m, mu, sd


def tick_games(ticks, unknown_of=lambda t: t[0]):
    """The ticks' games as arrays (gc, gr, gw): the unknown of the climber
    (unknown_of(tick); the climber index by default), the route, 1 for the
    climber's win; and the felt grades (fr, fv): route and value."""
    gc, gr, gw, fr, fv = [], [], [], [], []
    for t in ticks:
        r, outcome, attempts, felt = t[1], t[2], t[3], t[4]
        j = unknown_of(t)
        win, loss = games(outcome, attempts)
        gc += [j] * (win + loss)
        gr += [r] * (win + loss)
        gw += [1] * win + [0] * loss
        if felt is not None:
            fr.append(r)
            fv.append(felt)
    gc, gr, gw = np.array(gc, dtype=int), np.array(gr, dtype=int), np.array(gw, dtype=float)
    fr, fv = np.array(fr, dtype=int), np.array(fv, dtype=float)
    return gc, gr, gw, fr, fv


def games_nll(s, gc, gr, gw, a, d):
    """The games' negative log-likelihood at abilities a and difficulties d."""
    z = s * (a[gc] - d[gr])
    return -np.sum(gw * log_expit(z) + (1 - gw) * log_expit(-z))


def games_grad(s, gc, gr, gw, a, d, n):
    """Its gradient over n unknowns: a first, d from len(a)."""
    e = s * (expit(s * (a[gc] - d[gr])) - gw)  # d nll / d a for each game
    g = np.zeros(n)
    np.add.at(g, gc, e)
    np.add.at(g, len(a) + gr, -e)
    return g


def games_hess(s, gc, gr, a, d, n):
    """Its Hessian over n unknowns: a first, d from len(a)."""
    p = expit(s * (a[gc] - d[gr]))
    h = s * s * p * (1 - p)
    H = np.zeros((n, n))
    o = len(a)
    np.add.at(H, (gc, gc), h)
    np.add.at(H, (o + gr, o + gr), h)
    np.add.at(H, (gc, o + gr), -h)
    np.add.at(H, (o + gr, gc), -h)
    return H


def route_prior_grad(g, off, d, mu, sd, fr, fv, pf):
    """Adds the routes' priors and felt grades to the gradient g (route r at
    off + r)."""
    g[off:off + len(d)] += (d - mu) / sd ** 2
    np.add.at(g, off + fr, pf * (d[fr] - fv))


def route_prior_hess(H, off, sd, fr, pf):
    """Adds the routes' priors and felt grades to the Hessian H."""
    R = len(sd)
    H[off + np.arange(R), off + np.arange(R)] += 1 / sd ** 2
    np.add.at(H, (off + fr, off + fr), pf)


def polish(x, grad, hess):
    """Plain Newton steps from the minimiser's answer until the gradient is
    below 1e-11 (trust-exact can stop short on flat games)."""
    for _ in range(50):
        g = grad(x)
        if np.max(np.abs(g)) < 1e-11:
            break
        x = x - np.linalg.solve(hess(x), g)
    return x


def main(fit):
    """Reads sys.argv[1] ({"cases": [...]}), writes {"cases": [fit(case),
    ...]} to sys.argv[2]."""
    with open(sys.argv[1]) as fh:
        spec = json.load(fh)
    out = {"cases": [fit(c) for c in spec["cases"]]}
    with open(sys.argv[2], "w") as fh:
        json.dump(out, fh)
