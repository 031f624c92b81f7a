#!/usr/bin/env python3
# Usage: scripts/dashboard_bench.py URL ../shared/corpus  (a fresh `strangebeta serve`; docs/BENCHMARKS.md
# "Setting dashboard"). Needs python3-requests.
# Times GET /api/gyms/{g}/dashboard and /gyms/{g}/dashboard on the original site's 605 routes
# (../shared/corpus) imported into one gym and spread over 8 walls, all set, with ticks.
import json, random, sys, time, requests, statistics
base = sys.argv[1]; corpus = sys.argv[2]
s = requests.Session()
s.post(base + '/api/users', json={'username': 'bench', 'password': 'password123'})
r = s.post(base + '/api/sessions', json={'username': 'bench', 'password': 'password123'})
s.headers['X-CSRF-Token'] = r.json()['csrf']
gl = s.get(base + '/api/gyms').json()['gyms']
g = gl[0]['id'] if gl else s.post(base + '/api/gyms', json={'name': 'Bench'}).json()['id']
walls = []
for i in range(8):
    walls.append(s.post(f'{base}/api/gyms/{g}/walls', json={'name': f'W{i}', 'reset_weeks': 6,
        'plan': {'x': (i % 4) * 6, 'y': (i // 4) * 4, 'w': 5, 'h': 3}}).json()['id'])
imp = s.post(base + '/api/import/csv', json={'gym': g,
    'routes_csv': open(corpus + '/public_routes.csv').read(),
    'moves_csv': open(corpus + '/public_moves.csv').read()}).json()
ids = list(imp['ids'].values())
rnd = random.Random(1)
t0 = time.time()
for k, rid in enumerate(ids):
    s.put(f'{base}/api/routes/{rid}', json={'wall': str(walls[k % 8]), 'state': 'set',
          'set_on': f'2026-{rnd.randint(1, 11):02d}-{rnd.randint(1, 28):02d}'})
print('routes set:', len(ids), 'in', round(time.time() - t0, 1), 's')
s.put(f'{base}/api/gyms/{g}/walls/{walls[0]}/targets', json={'grades': {'V3': 20, 'V4': 20}, 'styles': {'crimp': 0.3}})
for path in [f'/api/gyms/{g}/dashboard', f'/gyms/{g}/dashboard']:
    first = time.time(); r = s.get(base + path); first = time.time() - first
    assert r.status_code == 200, r.text[:200]
    times = []
    for _ in range(30):
        t = time.time(); s.get(base + path); times.append(time.time() - t)
    times.sort()
    print(f'{path}: {len(r.content)} bytes, first {first*1000:.0f} ms, median {statistics.median(times)*1000:.0f} ms, max of 30 {times[-1]*1000:.0f} ms')
