#!/usr/bin/env python3
"""Latency under concurrent users (issue 22, docs/BENCHMARKS.md "A chain at scale").

Signs in N users of a synthetic chain (`strangebeta synth`: head setters head-1..head-N,
password synth-chain-password), each from its own loopback address (127.0.60.i, so the
per-address limits see N clients, as in a gym), finds each one's gym and walls through
the API, then has every user request pages for a fixed duration, one request at a time,
cycling through the URL kinds (so every kind gets about as many samples), and prints
p50/p95/p99/max per kind in milliseconds. Python stdlib only (threads + http.client,
keep-alive connections).

  bench/web_load.py --url http://127.0.0.1:8080 --users 20 --seconds 30
  bench/web_load.py --url ... --kinds gym,wall,api_wall --json out.json
  bench/web_load.py --url ... --think 1    # each user reads a page for 0..2 s (random, seeded)

Kinds (G = the user's gym, W = one of its walls, drawn per request):
  gym          /gyms/G                       the gym page (walls, circuits, members)
  wall         /walls/W                      a wall's page (its routes on the wall)
  list         /?gym=G&state=set&sort=age    the route list page, oldest on the wall first
  api_wall     /api/routes?gym=G&state=set&wall=W
  api_set      /api/routes?gym=G&state=set&sort=age
  api_archive  /api/routes?gym=G&state=stripped&sort=hardest
  api_deep     /api/routes?gym=G&state=stripped&offset=5000   (page 101 of the archive)
  api_setter   /api/routes?gym=G&setter=setter-G-1
  api_search   /api/routes?gym=G&q=crimp
  api_grade    /api/routes?gym=G&from=V3&to=V5&state=set
  dashboard    /gyms/G/dashboard             (skipped when the server answers 404)
  api_dashboard /api/gyms/G/dashboard        (skipped when the server answers 404)
Every /api/routes request asks for a page of 50 (limit=50, issue 21); the list page uses the
server's page size.
--think SECONDS (default 0: back to back, the harsh case): after each answer a user waits a
random 0..2*SECONDS (uniform, seeded per user by --seed), as people reading a page do.
A non-2xx answer counts as an error for its kind (the latency is still recorded).
"""
import argparse
import http.client
import json
import random
import sys
import threading
import time
import urllib.parse

KINDS = ['gym', 'wall', 'list', 'api_wall', 'api_set', 'api_archive', 'api_deep',
         'api_setter', 'api_search', 'api_grade', 'dashboard', 'api_dashboard']
OPTIONAL = {'dashboard', 'api_dashboard'}


def connect(host, port, src):
    return http.client.HTTPConnection(host, port, timeout=60, source_address=(src, 0))


def call(conn, method, path, body=None, headers=None):
    conn.request(method, path, body=body, headers=headers or {})
    r = conn.getresponse()
    data = r.read()
    return r.status, r.getheader('set-cookie'), data


def sign_in(host, port, src, username, password):
    conn = connect(host, port, src)
    body = json.dumps({'username': username, 'password': password}).encode()
    st, cookie, data = call(conn, 'POST', '/api/sessions', body,
                            {'Content-Type': 'application/json'})
    if st != 200 or not cookie:
        raise SystemExit('web_load.py: sign-in of %s failed: %d %s' % (username, st, data[:200]))
    headers = {'Cookie': cookie.split(';')[0], 'X-CSRF-Token': json.loads(data)['csrf']}
    st, _, data = call(conn, 'GET', '/api/gyms', headers=headers)
    if st != 200:
        raise SystemExit('web_load.py: GET /api/gyms for %s: %d' % (username, st))
    gyms = json.loads(data)['gyms']
    mine = [g for g in gyms if g.get('role') in ('head', 'setter')] or gyms
    if not mine:
        raise SystemExit('web_load.py: %s belongs to no gym' % username)
    gym = mine[0]['id']
    st, _, data = call(conn, 'GET', '/api/gyms/%d/walls' % gym, headers=headers)
    if st != 200:
        raise SystemExit('web_load.py: GET walls of gym %d: %d' % (gym, st))
    walls = [w['id'] for w in json.loads(data)['walls']]
    conn.close()  # the server may close idle connections while the others sign in
    return headers, gym, walls


def path_of(kind, gym, wall, setter):
    def q(d):
        if 'state' in d or 'q' in d or 'setter' in d:
            d = dict(d, limit=50)  # issue 21's page of 50 (the API's default is larger)
        return urllib.parse.urlencode(d)
    return {
        'gym': '/gyms/%d' % gym,
        'wall': '/walls/%d' % wall,
        'list': '/?' + urllib.parse.urlencode({'gym': gym, 'state': 'set', 'sort': 'age'}),
        'api_wall': '/api/routes?' + q({'gym': gym, 'state': 'set', 'wall': wall}),
        'api_set': '/api/routes?' + q({'gym': gym, 'state': 'set', 'sort': 'age'}),
        'api_archive': '/api/routes?' + q({'gym': gym, 'state': 'stripped', 'sort': 'hardest'}),
        'api_deep': '/api/routes?' + q({'gym': gym, 'state': 'stripped', 'offset': 5000}),
        'api_setter': '/api/routes?' + q({'gym': gym, 'setter': setter}),
        'api_search': '/api/routes?' + q({'gym': gym, 'q': 'crimp'}),
        'api_grade': '/api/routes?' + q({'gym': gym, 'from': 'V3', 'to': 'V5', 'state': 'set'}),
        'dashboard': '/gyms/%d/dashboard' % gym,
        'api_dashboard': '/api/gyms/%d/dashboard' % gym,
    }[kind]


def percentile(sorted_ms, p):
    """Nearest-rank percentile of an ascending list."""
    if not sorted_ms:
        return float('nan')
    k = max(0, min(len(sorted_ms) - 1, int(-(-p * len(sorted_ms) // 100)) - 1))
    return sorted_ms[k]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--url', required=True, help='the server, http://HOST:PORT')
    ap.add_argument('--users', type=int, default=20)
    ap.add_argument('--seconds', type=float, default=30)
    ap.add_argument('--user-format', default='head-%d', help='user names (%%d = 1..N)')
    ap.add_argument('--password', default='synth-chain-password')
    ap.add_argument('--kinds', default=','.join(KINDS))
    ap.add_argument('--warmup', type=float, default=2, help='seconds not recorded')
    ap.add_argument('--seed', type=int, default=1)
    ap.add_argument('--json', help='also write the figures here')
    ap.add_argument('--think', type=float, default=0,
                    help='mean seconds a user waits between requests (0..2x, seeded; 0 = none)')
    a = ap.parse_args()
    u = urllib.parse.urlsplit(a.url)
    host, port = u.hostname, u.port or 80
    kinds = [k for k in a.kinds.split(',') if k]
    for k in kinds:
        if k not in KINDS:
            raise SystemExit('web_load.py: unknown kind %r (known: %s)' % (k, ', '.join(KINDS)))
    if not 0 <= a.think <= 600:
        raise SystemExit('web_load.py: --think must be 0..600 seconds')
    if not 1 <= a.users <= 250:
        raise SystemExit('web_load.py: --users must be 1..250')

    users = []
    for i in range(1, a.users + 1):
        src = '127.0.60.%d' % i
        headers, gym, walls = sign_in(host, port, src, a.user_format % i, a.password)
        users.append((src, headers, gym, walls, 'setter-%d-1' % gym))
    # Kinds the server does not have (404 on the first user's gym) are left out.
    src, headers, gym, walls, setter = users[0]
    conn = connect(host, port, src)
    for k in list(kinds):
        if k in OPTIONAL:
            st, _, _ = call(conn, 'GET', path_of(k, gym, walls[0], setter), headers=headers)
            if st == 404:
                print('web_load.py: %s answers 404 here; left out' % k, file=sys.stderr)
                kinds.remove(k)

    samples = {k: [] for k in kinds}
    errors = {k: 0 for k in kinds}
    lock = threading.Lock()
    start = time.monotonic()
    record_from = start + a.warmup
    stop = record_from + a.seconds

    def worker(n, user):
        src, headers, gym, walls, setter = user
        conn = connect(host, port, src)
        rng = random.Random(a.seed * 1000 + n)
        # A second generator, so the walls drawn are the same with and without --think.
        think = random.Random('think-%d-%d' % (a.seed, n))
        mine = {k: [] for k in kinds}
        bad = {k: 0 for k in kinds}
        i = n  # users start at different kinds
        while True:
            now = time.monotonic()
            if now >= stop:
                break
            kind = kinds[i % len(kinds)]
            i += 1
            path = path_of(kind, gym, rng.choice(walls), setter)
            t0 = time.monotonic()
            try:
                st, _, _ = call(conn, 'GET', path, headers=headers)
            except (OSError, http.client.HTTPException):
                st = 0
                conn.close()
                conn = connect(host, port, src)
            ms = (time.monotonic() - t0) * 1000
            if t0 >= record_from:
                mine[kind].append(ms)
                if not 200 <= st < 300:
                    bad[kind] += 1
            if a.think > 0:
                time.sleep(max(0.0, min(think.uniform(0, 2 * a.think), stop - time.monotonic())))
        with lock:
            for k in kinds:
                samples[k].extend(mine[k])
                errors[k] += bad[k]

    threads = [threading.Thread(target=worker, args=(n, u)) for n, u in enumerate(users)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()

    out = {'users': a.users, 'seconds': a.seconds, 'kinds': {}}
    if a.think > 0:
        out['think'] = a.think
    print('%-14s %7s %6s %9s %9s %9s %9s' % ('kind', 'n', 'errors', 'p50 ms', 'p95 ms',
                                            'p99 ms', 'max ms'))
    for k in kinds:
        s = sorted(samples[k])
        row = {'n': len(s), 'errors': errors[k], 'p50': percentile(s, 50),
               'p95': percentile(s, 95), 'p99': percentile(s, 99),
               'max': s[-1] if s else float('nan')}
        out['kinds'][k] = row
        print('%-14s %7d %6d %9.1f %9.1f %9.1f %9.1f' % (k, row['n'], row['errors'], row['p50'],
                                                        row['p95'], row['p99'], row['max']))
    total = sum(len(v) for v in samples.values())
    print('%d requests in %.0f s by %d users (%.0f/s)' % (total, a.seconds, a.users,
                                                         total / a.seconds))
    if a.json:
        with open(a.json, 'w') as f:
            json.dump(out, f, indent=1, sort_keys=True)
    return 1 if any(errors.values()) else 0


if __name__ == '__main__':
    sys.exit(main())
