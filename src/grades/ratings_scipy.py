#!/usr/bin/python3
"""SciPy reference for the ascent rating (src/grades/ratings_scipy_test.cc).

Usage: /usr/bin/python3 ratings_scipy.py IN.json OUT.json

IN.json: {"cases": [{"params": {"logit_per_unit", "climber_sd", "setter_sd",
"open_route_sd", "felt_sd"}, "climbers": C, "routes": R, "setter": [value or
null per route], "ticks": [[climber, route, "flash"|"send"|"attempt",
attempts or null, felt value or null], ...], optional "model": "tries" |
"session", optional "pairs": [[climber, route], ...] (an index past the
climbers or routes is one not seen: at the prior)}, ...]}
OUT.json: {"cases": [{"difficulty": [...], "difficulty_sd": [...],
"ability": [...], "ability_sd": [...], "prior_mean": m, "success": bool,
"session_offset": b, "p_flash": [...], "p_send": [...]}]}

An independent re-implementation of the model of docs/grades.md ("Grades
from ascents") on numpy/scipy, sharing no code with the C++ module: every
tick is expanded into its games here (flash = 1 win; send after n tries =
n - 1 losses and a win, n empty = 2; attempt = n losses, n empty = 1), the
negative log posterior is minimised by scipy.optimize.minimize
(trust-exact, with its gradient and Hessian written out from the formula),
and the standard deviations are the square roots of the diagonal of the
inverse Hessian (numpy.linalg.inv).

The session model (docs/grades.md, "A model of the session") is written out
here the same way: each tick is a first-try game (won by a flash) at
s(k (a - d)) and a session game (won by any send) at s(k (a - d) + b), the
offset b one more unknown with prior N(2, 2^2), minimised jointly with the
rest; the standard deviations are those of the abilities and difficulties
with b held at its optimum (the inverse of their block of the Hessian).
Predictions: p_flash = s(k (a - d)); p_send = s(k (a - d) + b) (session) or
1 - (1 - p_flash)^T (tries; T the mean tries of the ticks with a known
count, a flash one try).
The session model with zones and session offsets ("model": "session_zones",
fit_session_zones below; ratings_session.h) takes rows of competition
results instead of ticks.
Exit code 3 when scipy is missing (the test then skips with a message).
The reading of a case, the games of a tick and the Newton polish are
ratings_oracle.py's (shared with ratings_drift_scipy.py).
"""
from ratings_oracle import (expit, games_grad, games_hess, games_nll, log_expit, main, np,
                            optimize, polish, route_prior_grad, route_prior_hess, route_priors,
                            tick_games)


def fit(case):
    if case.get("model") == "session":
        return fit_session(case)
    if case.get("model") == "session_zones":
        return fit_session_zones(case)
    k = case["params"]
    s = k["logit_per_unit"]
    C, R = case["climbers"], case["routes"]
    m, mu, sd = route_priors(case)
    # One row per game: climber index, route index, 1 for a climber's win.
    gc, gr, gw, fr, fv = tick_games(case["ticks"])
    pa = 1.0 / k["climber_sd"] ** 2
    pf = 1.0 / k["felt_sd"] ** 2
    n = C + R

    def f(x):
        a, d = x[:C], x[C:]
        nll = games_nll(s, gc, gr, gw, a, d)
        nll += 0.5 * pa * np.sum((a - m) ** 2)
        nll += 0.5 * np.sum(((d - mu) / sd) ** 2)
        nll += 0.5 * pf * np.sum((fv - d[fr]) ** 2)
        return nll

    def grad(x):
        a, d = x[:C], x[C:]
        g = games_grad(s, gc, gr, gw, a, d, n)
        g[:C] += pa * (a - m)
        route_prior_grad(g, C, d, mu, sd, fr, fv, pf)
        return g

    def hess(x):
        H = games_hess(s, gc, gr, x[:C], x[C:], n)
        H[np.arange(C), np.arange(C)] += pa
        route_prior_hess(H, C, sd, fr, pf)
        return H

    x0 = np.concatenate([np.full(C, m), mu])
    res = optimize.minimize(f, x0, jac=grad, hess=hess, method="trust-exact",
                            options={"gtol": 1e-12, "maxiter": 1000})
    x = res.x
    cov = np.linalg.inv(hess(x))
    sds = np.sqrt(np.diag(cov))
    out = {"difficulty": x[C:].tolist(), "difficulty_sd": sds[C:].tolist(),
           "ability": x[:C].tolist(), "ability_sd": sds[:C].tolist(), "prior_mean": m,
           "session_offset": 0.0, "success": bool(np.max(np.abs(grad(x))) < 1e-8)}
    tries = []
    for _, _, outcome, attempts, _ in case["ticks"]:
        if attempts is not None:
            tries.append(attempts)
        elif outcome == "flash":
            tries.append(1)
    T = max(1.0, float(np.mean(tries))) if tries else 1.0
    pf = predict(case, x[:C], x[C:], m, s)
    out["p_flash"] = pf.tolist()
    out["p_send"] = (1 - (1 - pf) ** T).tolist()
    return out


def predict(case, a, d, m, s, offset=0.0):
    """s(k (a - d) + offset) per pair; unseen climbers and routes at m."""
    res = []
    for c, r in case.get("pairs", []):
        ac = a[c] if c < len(a) else m
        dr = d[r] if r < len(d) else m
        res.append(expit(s * (ac - dr) + offset))
    return np.array(res, dtype=float)


def fit_session(case):
    """The session model: a first-try game and a session game per tick."""
    k = case["params"]
    s = k["logit_per_unit"]
    C, R = case["climbers"], case["routes"]
    m, mu, sd = route_priors(case)
    gc, gr, gw, gs, fr, fv = [], [], [], [], [], []
    for c, r, outcome, attempts, felt in case["ticks"]:
        # first try: won only by a flash; session: won by a flash or a send
        gc += [c, c]
        gr += [r, r]
        gw += [1.0 if outcome == "flash" else 0.0, 0.0 if outcome == "attempt" else 1.0]
        gs += [0.0, 1.0]
        if felt is not None:
            fr.append(r)
            fv.append(felt)
    gc, gr = np.array(gc, dtype=int), np.array(gr, dtype=int)
    gw, gs = np.array(gw), np.array(gs)
    fr, fv = np.array(fr, dtype=int), np.array(fv, dtype=float)
    pa = 1.0 / k["climber_sd"] ** 2
    pf = 1.0 / k["felt_sd"] ** 2
    b0, pb = 2.0, 1.0 / 2.0 ** 2
    n = C + R  # x = [a, d, b]

    def z_of(x):
        return s * (x[:C][gc] - x[C:n][gr]) + gs * x[n]

    def f(x):
        a, d, b = x[:C], x[C:n], x[n]
        z = z_of(x)
        nll = -np.sum(gw * log_expit(z) + (1 - gw) * log_expit(-z))
        nll += 0.5 * pa * np.sum((a - m) ** 2) + 0.5 * np.sum(((d - mu) / sd) ** 2)
        nll += 0.5 * pf * np.sum((fv - d[fr]) ** 2) + 0.5 * pb * (b - b0) ** 2
        return nll

    def grad(x):
        a, d, b = x[:C], x[C:n], x[n]
        e = expit(z_of(x)) - gw
        g = np.zeros(n + 1)
        np.add.at(g, gc, s * e)
        np.add.at(g, C + gr, -s * e)
        g[n] = np.sum(gs * e) + pb * (b - b0)
        g[:C] += pa * (a - m)
        route_prior_grad(g, C, d, mu, sd, fr, fv, pf)
        return g

    def hess(x):
        p = expit(z_of(x))
        w = p * (1 - p)
        H = np.zeros((n + 1, n + 1))
        np.add.at(H, (gc, gc), s * s * w)
        np.add.at(H, (C + gr, C + gr), s * s * w)
        np.add.at(H, (gc, C + gr), -s * s * w)
        np.add.at(H, (C + gr, gc), -s * s * w)
        np.add.at(H, (gc, np.full(len(gc), n)), s * gs * w)
        np.add.at(H, (np.full(len(gc), n), gc), s * gs * w)
        np.add.at(H, (C + gr, np.full(len(gr), n)), -s * gs * w)
        np.add.at(H, (np.full(len(gr), n), C + gr), -s * gs * w)
        H[n, n] = np.sum(gs * w) + pb
        H[np.arange(C), np.arange(C)] += pa
        route_prior_hess(H, C, sd, fr, pf)
        return H

    x0 = np.concatenate([np.full(C, m), mu, [b0]])
    res = optimize.minimize(f, x0, jac=grad, hess=hess, method="trust-exact",
                            options={"gtol": 1e-8, "maxiter": 1000})
    x = polish(res.x, grad, hess)
    cov = np.linalg.inv(hess(x)[:n, :n])
    sds = np.sqrt(np.diag(cov))
    b = float(x[n])
    return {"difficulty": x[C:n].tolist(), "difficulty_sd": sds[C:].tolist(),
            "ability": x[:C].tolist(), "ability_sd": sds[:C].tolist(), "prior_mean": m,
            "session_offset": b, "success": bool(np.max(np.abs(grad(x))) < 1e-8),
            "p_flash": predict(case, x[:C], x[C:n], m, s).tolist(),
            "p_send": predict(case, x[:C], x[C:n], m, s, b).tolist()}


def fit_session_zones(case):
    """The session model with zones and session offsets (ratings_session.h).

    case: {"model": "session_zones", "params": {"logit_per_unit", "climber_sd",
    "route_sd", "zone_sd", "route_offset_sd", "climber_offset_sd",
    "offset_mean", "offset_sd", "delta_sd", "prior_mean", "later_tries_weight"},
    "climbers": C,
    "routes": R, "rows": [[climber, route, top 0/1, tries or null, zone 0/1 or
    null, zone_tries or null], ...], "pairs": [...]}. Written from the
    docs' formula: per row a first-try game s(k (a - d)) won by a top in one
    try and a session game s(k (a - d) + b + e_r + u_c) won by a top (none
    with 0 tries) and, at weight later_tries_weight, one per-try game
    s(k (a - d)) per try after the first (the topping try won); with a zone, a first-try zone game s(k (a - z_r)) (zone
    tries known) and a session zone game s(k (a - z_r) + b); priors a, d ~
    N(m, sd^2), z_r - d_r + delta ~ N(0, zone_sd^2), e_r, u_c ~ N(0, sd^2),
    b ~ N(offset_mean, offset_sd^2), delta ~ N(0, delta_sd^2). Dense design
    matrix X (games x unknowns), minimised by trust-exact with the exact
    Hessian X' W X + priors, then polished by Newton.
    """
    k = case["params"]
    s = k["logit_per_unit"]
    C, R = case["climbers"], case["routes"]
    m = k["prior_mean"]
    # x = [a (C), d (R), z (R), e (R), u (C), b, delta]
    ia, id_, iz, ie, iu = 0, C, C + R, C + 2 * R, C + 3 * R
    ib, idl = 2 * C + 3 * R, 2 * C + 3 * R + 1
    n = idl + 1
    rows, y, wts_extra = [], [], []
    for c, r, top, tries, zone, zt in case["rows"]:
        if tries != 0:
            v = np.zeros(n)
            v[ia + c], v[id_ + r] = s, -s
            rows.append(v.copy())
            y.append(1.0 if (top and tries == 1) else 0.0)
            v[ib] = 1.0
            if k["route_offset_sd"] > 0:
                v[ie + r] = 1.0
            if k["climber_offset_sd"] > 0:
                v[iu + c] = 1.0
            rows.append(v)
            y.append(1.0 if top else 0.0)
            lw = k.get("later_tries_weight", 0.0)
            if lw > 0 and tries is not None and tries > 1:
                # the later tries: one game per try, each at weight lw
                lost = tries - 2 if top else tries - 1
                v = np.zeros(n)
                v[ia + c], v[id_ + r] = s, -s
                for _ in range(lost):
                    rows.append(v.copy())
                    y.append(0.0)
                    wts_extra.append(len(rows) - 1)
                if top:
                    rows.append(v.copy())
                    y.append(1.0)
                    wts_extra.append(len(rows) - 1)
        if k["zone_sd"] > 0 and zone is not None and zt != 0:
            v = np.zeros(n)
            v[ia + c], v[iz + r] = s, -s
            if zt is not None:
                rows.append(v.copy())
                y.append(1.0 if (zone and zt == 1) else 0.0)
            v[ib] = 1.0
            rows.append(v)
            y.append(1.0 if zone else 0.0)
    X, y = np.array(rows), np.array(y)
    wt = np.ones(len(y))
    wt[wts_extra] = k.get("later_tries_weight", 0.0)
    # priors: rows of Pm x - mu with precisions lam
    Pm, mu, lam = [], [], []

    def prior(terms, mean, sd):
        v = np.zeros(n)
        for j, c in terms:
            v[j] += c
        Pm.append(v)
        mu.append(mean)
        lam.append(1.0 / sd ** 2)

    for c in range(C):
        prior([(ia + c, 1)], m, k["climber_sd"])
        prior([(iu + c, 1)], 0.0, k["climber_offset_sd"] or 1.0)
    for r in range(R):
        prior([(id_ + r, 1)], m, k["route_sd"])
        if k["zone_sd"] > 0:
            prior([(iz + r, 1), (id_ + r, -1), (idl, 1)], 0.0, k["zone_sd"])
        else:
            prior([(iz + r, 1)], 0.0, 1.0)
        prior([(ie + r, 1)], 0.0, k["route_offset_sd"] or 1.0)
    prior([(ib, 1)], k["offset_mean"], k["offset_sd"])
    prior([(idl, 1)], 0.0, k["delta_sd"])
    Pm, mu, lam = np.array(Pm), np.array(mu), np.array(lam)

    def f(x):
        z = X @ x
        r = Pm @ x - mu
        return (-np.sum(wt * (y * log_expit(z) + (1 - y) * log_expit(-z)))
                + 0.5 * np.sum(lam * r * r))

    def grad(x):
        return X.T @ (wt * (expit(X @ x) - y)) + Pm.T @ (lam * (Pm @ x - mu))

    def hess(x):
        p = expit(X @ x)
        return (X.T * (wt * p * (1 - p))) @ X + (Pm.T * lam) @ Pm

    x0 = np.zeros(n)
    x0[ia:ia + C] = m
    x0[id_:iz + R] = m
    x0[ib] = k["offset_mean"]
    res = optimize.minimize(f, x0, jac=grad, hess=hess, method="trust-exact",
                            options={"gtol": 1e-8, "maxiter": 1000})
    x = polish(res.x, grad, hess)
    pf, ps = [], []
    for c, r in case.get("pairs", []):
        a = x[ia + c] if c < C else m
        d = x[id_ + r] if r < R else m
        u = x[iu + c] if c < C else 0.0
        e = x[ie + r] if r < R else 0.0
        pf.append(float(expit(s * (a - d))))
        ps.append(float(expit(s * (a - d) + x[ib] + e + u)))
    return {"ability": x[ia:ia + C].tolist(), "difficulty": x[id_:id_ + R].tolist(),
            "zone_difficulty": x[iz:iz + R].tolist(), "route_offset": x[ie:ie + R].tolist(),
            "climber_offset": x[iu:iu + C].tolist(), "offset": float(x[ib]),
            "delta": float(x[idl]), "success": bool(np.max(np.abs(grad(x))) < 1e-8),
            "p_flash": pf, "p_send": ps}


if __name__ == "__main__":
    main(fit)
