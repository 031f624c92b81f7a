#!/usr/bin/env python3
"""A setting-day proposal on the synthetic chain, timed (issue 22, docs/BENCHMARKS.md
"Setting-day proposal on the chain").

Signs in as head-G of the chain (`strangebeta synth`, password synth-chain-password),
reads the gym's walls and posts `POST /api/gyms/G/setting-days` with all of them,
`"candidates": 6`, `"date": "2099-12-01"` (no slots: the dashboard's gap slots), RUNS
times, one request at a time; prints each request's status, wall time, slots and
candidates. With OUT, the last reply's JSON is written there (compare two builds' with
cmp: the proposal is deterministic). Python stdlib only.

  bench/setting_day_chain.py PORT [RUNS] [OUT] [GYM] [write]

With `write` (fifth argument; OUT may be `-` for none), each run is preceded by a write to the
gym (`PUT /api/gyms/G/walls/W/targets` on its first wall, a different count each time), so every
proposal is the first after a write: the dashboard model is built again (its cache keys on the
gym's data version); the PUT's time is not counted.
"""
import http.client
import json
import sys
import time

port = int(sys.argv[1])
runs = int(sys.argv[2]) if len(sys.argv) > 2 else 1
out = sys.argv[3] if len(sys.argv) > 3 and sys.argv[3] != '-' else None
gym = int(sys.argv[4]) if len(sys.argv) > 4 else 1
write = len(sys.argv) > 5 and sys.argv[5] == 'write'


def conn():
    return http.client.HTTPConnection('127.0.0.1', port, timeout=600)


c = conn()
c.request('POST', '/api/sessions',
          body=json.dumps({'username': 'head-%d' % gym, 'password': 'synth-chain-password'}),
          headers={'Content-Type': 'application/json'})
r = c.getresponse()
session = json.loads(r.read())
h = {'Cookie': r.getheader('set-cookie').split(';')[0], 'Content-Type': 'application/json',
     'X-CSRF-Token': session['csrf']}
c = conn()
c.request('GET', '/api/gyms/%d/walls' % gym, headers=h)
walls = [w['id'] for w in json.loads(c.getresponse().read())['walls']]
body = json.dumps({'date': '2099-12-01', 'walls': walls, 'candidates': 6})
band = None
if write:
    c = conn()
    c.request('GET', '/api/gyms/%d/dashboard' % gym, headers=h)
    first = json.loads(c.getresponse().read())['walls'][0]
    band = sorted(first['grades'])[0]
for i in range(runs):
    if write:
        c = conn()
        c.request('PUT', '/api/gyms/%d/walls/%d/targets' % (gym, walls[0]),
                  body=json.dumps({'grades': {band: 10 + i}}), headers=h)
        r = c.getresponse()
        r.read()
        if r.status != 200:
            print('write', i + 1, r.status, flush=True)
    t = time.time()
    c = conn()
    c.request('POST', '/api/gyms/%d/setting-days' % gym, body=body, headers=h)
    r = c.getresponse()
    d = r.read()
    dt = time.time() - t
    j = json.loads(d) if r.status == 200 else None
    if j is None:
        print('run', i + 1, r.status, '%.2f s' % dt, d[:200].decode(errors='replace'), flush=True)
        continue
    n = sum(len(s['candidates']) for s in j['slots'])
    print('run', i + 1, r.status, '%.2f s' % dt, len(walls), 'walls', len(j['slots']), 'slots',
          n, 'candidates', flush=True)
    if out:
        with open(out, 'w') as f:
            f.write(d.decode())
