#!/usr/bin/python3
"""SciPy reference for the drifting ascent rating (ratings_drift_scipy_test.cc).

Usage: /usr/bin/python3 ratings_drift_scipy.py IN.json OUT.json

IN.json: {"cases": [{"params": {"logit_per_unit", "climber_sd", "setter_sd",
"open_route_sd", "felt_sd"}, "climbers": C, "routes": R, "setter": [value or
null per route], "ticks": [[climber, route, "flash"|"send"|"attempt",
attempts or null, felt value or null, day], ...], "w": W, "node_days": 7}]}
OUT.json: {"cases": [{"difficulty", "difficulty_sd", "ability" (each
climber's latest node), "ability_sd", "log_evidence", "success"}]}

An independent re-implementation of docs/grades.md ("Abilities that drift")
on numpy/scipy, sharing no code with the C++ module: each tick is expanded
into its games (the tries model); a climber's ticks are grouped by week
(days from the first tick's day, integer-divided by node_days), one unknown
per climber per week (a climber without ticks: one); the negative log
posterior (games; first week ~ N(m, climber_sd^2); consecutive weeks differ
by N(0, w^2 dt), dt = days / 365.25; routes' priors and felt grades as the
static model) is minimised by scipy.optimize.minimize (trust-exact) and
polished by Newton; the sds are the square roots of the diagonal of the
dense inverse Hessian; the Laplace log evidence is -f(x) + sum(log link
precision) / 2 - log det(H) / 2 (numpy.linalg.slogdet), up to constants free
of w (the felt grades' sum(f^2) / 2 felt_sd^2 is left out, as the C++ does).
Exit code 3 when scipy is missing (the test then skips with a message).
The reading of a case, the games of a tick and the Newton polish are
ratings_oracle.py's (shared with ratings_scipy.py).
"""
from ratings_oracle import (games_grad, games_hess, games_nll, main, np, optimize, polish,
                            route_prior_grad, route_prior_hess, route_priors, tick_games)


def fit(case):
    k = case["params"]
    s = k["logit_per_unit"]
    C, R = case["climbers"], case["routes"]
    w, node_days = case["w"], case["node_days"]
    m, mu, sd = route_priors(case)
    first = min(t[5] for t in case["ticks"])
    keys = sorted({(t[0], (t[5] - first) // node_days) for t in case["ticks"]} |
                  {(c, 0) for c in range(C) if not any(t[0] == c for t in case["ticks"])})
    node = {key: i for i, key in enumerate(keys)}
    N = len(keys)
    gc, gr, gw, fr, fv = tick_games(case["ticks"],
                                    lambda t: node[(t[0], (t[5] - first) // node_days)])
    firsts = [i for i, key in enumerate(keys) if i == 0 or keys[i - 1][0] != key[0]]
    links = []  # (i, i + 1, precision)
    for i in range(N - 1):
        if keys[i][0] == keys[i + 1][0]:
            dt = (keys[i + 1][1] - keys[i][1]) * node_days / 365.25
            links.append((i, i + 1, 1.0 / (w * w * dt)))
    latest = [max(i for i, key in enumerate(keys) if key[0] == c) for c in range(C)]
    pa, pf = 1.0 / k["climber_sd"] ** 2, 1.0 / k["felt_sd"] ** 2
    n = N + R

    def f(x):
        a, d = x[:N], x[N:]
        v = games_nll(s, gc, gr, gw, a, d)
        v += 0.5 * pa * np.sum((a[firsts] - m) ** 2)
        v += sum(0.5 * q * (a[j] - a[i]) ** 2 for i, j, q in links)
        v += 0.5 * np.sum(((d - mu) / sd) ** 2) + 0.5 * pf * np.sum((fv - d[fr]) ** 2)
        return v

    def grad(x):
        a, d = x[:N], x[N:]
        g = games_grad(s, gc, gr, gw, a, d, n)
        g[firsts] += pa * (a[firsts] - m)
        for i, j, q in links:
            g[i] -= q * (a[j] - a[i])
            g[j] += q * (a[j] - a[i])
        route_prior_grad(g, N, d, mu, sd, fr, fv, pf)
        return g

    def hess(x):
        H = games_hess(s, gc, gr, x[:N], x[N:], n)
        H[firsts, firsts] += pa
        for i, j, q in links:
            H[i, i] += q
            H[j, j] += q
            H[i, j] -= q
            H[j, i] -= q
        route_prior_hess(H, N, sd, fr, pf)
        return H

    x0 = np.concatenate([np.full(N, m), mu])
    res = optimize.minimize(f, x0, jac=grad, hess=hess, method="trust-exact",
                            options={"gtol": 1e-10, "maxiter": 1000})
    x = polish(res.x, grad, hess)
    H = hess(x)
    sds = np.sqrt(np.diag(np.linalg.inv(H)))
    _, logdet = np.linalg.slogdet(H)
    ev = -f(x) + 0.5 * sum(np.log(q) for _, _, q in links) - 0.5 * logdet
    # The C++ objective leaves out the felt grades' constant sum(f^2) / 2
    # felt_sd^2 (free of every unknown and of w): the same here.
    ev += 0.5 * pf * float(np.sum(fv ** 2))
    return {"difficulty": x[N:].tolist(), "difficulty_sd": sds[N:].tolist(),
            "ability": [float(x[i]) for i in latest],
            "ability_sd": [float(sds[i]) for i in latest],
            "log_evidence": float(ev), "nodes": N,
            "success": bool(np.max(np.abs(grad(x))) < 1e-8)}


if __name__ == "__main__":
    main(fit)
