#!/usr/bin/env python3
"""Durability test (docs/testing.md, "Durability test").

    durability.py BUILD_DIR [SOURCE_DIR] [ROUNDS]

ROUNDS times (default 5): start `strangebeta serve` on the same SQLite file,
log in, write routes from 4 threads (POST /api/routes) and `kill -9` the
server after a random 0.5-1.5 s of load. After each kill, every write the
server acknowledged (201 with an id) must be in the database with its text,
and `PRAGMA integrity_check` must say ok. Prints kills survived and writes
kept. Exit 0 on success, 1 on failure.
"""
import http.client
import json
import os
import random
import re
import signal
import sqlite3
import subprocess
import sys
import tempfile
import threading
import time

WRITERS = 4


def start(build, db, log_path):
    log = open(log_path, 'w+')
    proc = subprocess.Popen([os.path.join(build, 'strangebeta'), 'serve', '--port', '0', '--db',
                             db, '--no-seed'], stdout=log, stderr=subprocess.STDOUT)
    for _ in range(300):
        log.seek(0)
        m = re.search(r'http://127\.0\.0\.1:(\d+)/', log.read())
        if m:
            return proc, int(m.group(1))
        time.sleep(0.1)
    proc.kill()
    raise SystemExit('durability.py: the server did not start')


def call(port, method, path, body=None, headers=None):
    c = http.client.HTTPConnection('127.0.0.1', port, timeout=10)
    try:
        c.request(method, path, body=json.dumps(body) if body is not None else None,
                  headers=headers or {})
        r = c.getresponse()
        return r.status, r.getheader('Set-Cookie'), r.read()
    finally:
        c.close()


def writer(port, auth, tag, acked, lock, stop):
    i = 0
    conn = http.client.HTTPConnection('127.0.0.1', port, timeout=10)
    while not stop.is_set():
        name = '%s-%d' % (tag, i)
        crdl = 'name: %s\n---\nR jug\nL crimp\nR sloper\n' % name
        try:
            conn.request('POST', '/api/routes', body=json.dumps({'crdl': crdl}), headers=auth)
            r = conn.getresponse()
            body = r.read()
        except (OSError, http.client.HTTPException):
            return  # the server was killed: this write was never acknowledged
        if r.status == 201:
            with lock:
                acked.append((json.loads(body)['id'], name))
        i += 1


def main():
    build = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else 'build')
    rounds = int(sys.argv[3]) if len(sys.argv) > 3 else 5
    rng = random.Random(11)
    failures = 0
    with tempfile.TemporaryDirectory() as tmp:
        db = os.path.join(tmp, 'durable.db')
        acked = []
        for rnd in range(rounds):
            proc, port = start(build, db, os.path.join(tmp, 'serve%d.log' % rnd))
            user = {'username': 'writer', 'password': 'a-long-password'}
            json_type = {'Content-Type': 'application/json'}
            if rnd == 0:
                st, _, _ = call(port, 'POST', '/api/users', user, json_type)
                assert st == 201, st
            st, cookie, body = call(port, 'POST', '/api/sessions', user, json_type)
            assert st == 200, (st, body)
            auth = dict(json_type, Cookie=cookie.split(';')[0],
                        **{'X-CSRF-Token': json.loads(body)['csrf']})
            lock, stop = threading.Lock(), threading.Event()
            mine = []
            ts = [threading.Thread(target=writer,
                                   args=(port, auth, 'r%dw%d' % (rnd, w), mine, lock, stop))
                  for w in range(WRITERS)]
            for t in ts:
                t.start()
            time.sleep(rng.uniform(0.5, 1.5))
            os.kill(proc.pid, signal.SIGKILL)
            proc.wait()
            stop.set()
            for t in ts:
                t.join()
            acked += mine
            con = sqlite3.connect(db)
            integrity = con.execute('PRAGMA integrity_check').fetchone()[0]
            stored = dict(con.execute('SELECT id, crdl FROM routes').fetchall())
            con.close()
            missing = [(i, n) for i, n in acked
                       if i not in stored or ('name: %s\n' % n) not in stored[i]]
            ok = integrity == 'ok' and not missing
            print('%s round %d: kill -9 after %d acknowledged writes this round; %d in all, '
                  '%d missing; integrity_check %s' % ('ok  ' if ok else 'FAIL', rnd + 1,
                                                      len(mine), len(acked), len(missing),
                                                      integrity), flush=True)
            failures += not ok
    print('durability: %d of %d kills survived, %d acknowledged writes kept' %
          (rounds - failures, rounds, len(acked) if not failures else -1))
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
