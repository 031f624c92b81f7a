#!/usr/bin/env python3
"""Abuse test of the web server (docs/testing.md, "Abuse test").

    abuse.py BUILD_DIR [SOURCE_DIR]

Starts `strangebeta serve` on a temporary database (loopback, port 0) and
attacks it with cheap requests while a prober sends one normal request
(GET /api/routes?limit=1, a new connection each time) every 100 ms:

  chunked 100 MB body, gzip body, oversized header block, too many header
  fields, slowloris (300 connections from 127.0.0.2 sending one header byte
  every 2 s, beyond the per-address cap), 64 parallel log-in guesses, an
  anonymous IC map over the cost cap, a stream of IC maps under the cap
  until the budget is spent, a 2 MiB editor-feedback body, id reuse after a
  delete.

Each attack asserts the server's own refusal (413, 415, 431, 503, 401/429,
429 + Retry-After, ...). Throughout, every normal request must be answered
200 within 1 s; the worst latency is printed. Peak memory (VmHWM) must stay
under 512 MiB. Bounded to about a minute. Exit 0 on success, 1 on failure.
"""
import json
import os
import re
import socket
import subprocess
import sys
import tempfile
import threading
import time
import urllib.parse

MAX_LATENCY = 1.0  # seconds, for every normal request
MAX_PEAK_RSS_KB = 512 * 1024

failures = []


def check(cond, what):
    print(('ok   ' if cond else 'FAIL ') + what, flush=True)
    if not cond:
        failures.append(what)


class Server:
    def __init__(self, build, source, tmp):
        self.log = open(os.path.join(tmp, 'serve.log'), 'w+')
        self.proc = subprocess.Popen(
            [os.path.join(build, 'strangebeta'), 'serve', '--port', '0', '--db',
             os.path.join(tmp, 'abuse.db'), '--seed-examples',
             os.path.join(source, 'data', 'examples')],
            stdout=self.log, stderr=subprocess.STDOUT)
        self.port = None
        for _ in range(300):
            self.log.seek(0)
            m = re.search(r'http://127\.0\.0\.1:(\d+)/', self.log.read())
            if m:
                self.port = int(m.group(1))
                break
            time.sleep(0.1)
        if self.port is None:
            self.stop()
            raise SystemExit('abuse.py: the server did not start')

    def peak_rss_kb(self):
        with open('/proc/%d/status' % self.proc.pid) as f:
            for line in f:
                if line.startswith('VmHWM:'):
                    return int(line.split()[1])
        return 0

    def stop(self):
        self.proc.terminate()
        try:
            self.proc.wait(10)
        except subprocess.TimeoutExpired:
            self.proc.kill()
        return self.proc.returncode


def connect(port, source='127.0.0.1', timeout=10):
    s = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
    s.settimeout(timeout)
    s.bind((source, 0))
    s.connect(('127.0.0.1', port))
    return s


def read_response(s):
    """(status, headers dict lower-case, body) of one response; body read by Content-Length."""
    data = b''
    while b'\r\n\r\n' not in data:
        chunk = s.recv(65536)
        if not chunk:
            break
        data += chunk
    head, _, body = data.partition(b'\r\n\r\n')
    lines = head.decode('latin-1').split('\r\n')
    if not lines or not lines[0].startswith('HTTP/'):
        return None, {}, b''
    status = int(lines[0].split()[1])
    headers = {}
    for line in lines[1:]:
        k, _, v = line.partition(':')
        headers[k.strip().lower()] = v.strip()
    n = int(headers.get('content-length', '0'))
    while len(body) < n:
        chunk = s.recv(65536)
        if not chunk:
            break
        body += chunk
    return status, headers, body


def request(port, method, path, body=b'', headers=None, source='127.0.0.1', timeout=10):
    s = connect(port, source, timeout)
    try:
        h = {'Host': '127.0.0.1:%d' % port, 'Connection': 'close'}
        if body or method in ('POST', 'PUT'):
            h['Content-Length'] = str(len(body))
        h.update(headers or {})
        text = '%s %s HTTP/1.1\r\n' % (method, path)
        text += ''.join('%s: %s\r\n' % kv for kv in h.items()) + '\r\n'
        s.sendall(text.encode() + body)
        return read_response(s)
    finally:
        s.close()


class Prober(threading.Thread):
    """One normal request every 100 ms; records each latency and failure."""

    def __init__(self, port):
        super().__init__(daemon=True)
        self.port = port
        self.stop_flag = threading.Event()
        self.latencies = []
        self.bad = []

    def run(self):
        while not self.stop_flag.is_set():
            t = time.monotonic()
            try:
                status, _, body = request(self.port, 'GET', '/api/routes?limit=1', timeout=5)
                ok = status == 200 and b'"routes"' in body
            except OSError as e:
                ok, status = False, str(e)
            dt = time.monotonic() - t
            self.latencies.append(dt)
            if not ok or dt > MAX_LATENCY:
                self.bad.append((round(dt, 3), status))
            self.stop_flag.wait(0.1)


def chunked_flood(port):
    """A chunked body of up to 100 MB: refused with 413 after the limit (2 MiB)."""
    s = connect(port, '127.0.0.5', timeout=15)
    s.sendall(b'POST /api/routes HTTP/1.1\r\nHost: x\r\nContent-Type: application/json\r\n'
              b'Transfer-Encoding: chunked\r\n\r\n')
    chunk = b'%x\r\n%s\r\n' % (1 << 16, b'a' * (1 << 16))
    sent = 0
    try:
        while sent < 100 * 1024 * 1024:
            s.sendall(chunk)
            sent += 1 << 16
    except OSError:
        pass
    try:
        status, _, _ = read_response(s)
    except OSError:
        status = None
    s.close()
    check(sent < 16 * 1024 * 1024, 'chunked flood: server stopped reading after %d KiB' %
          (sent // 1024))
    check(status in (413, None), 'chunked flood: answered %s (413 or reset)' % status)


def refusals(port):
    import gzip
    bomb = gzip.compress(b'{"crdl":"' + b' ' * (50 * 1024 * 1024) + b'"}')
    st, _, _ = request(port, 'POST', '/api/feedback', bomb,
                       {'Content-Type': 'application/json', 'Content-Encoding': 'gzip'})
    check(st == 415, 'gzip body of %d KiB (50 MiB inflated): %s (415)' % (len(bomb) // 1024, st))
    st, _, _ = request(port, 'GET', '/api/routes', headers={'X-Big': 'a' * 100000})
    check(st == 431, '100 KB header: %s (431)' % st)
    many = {'X-F%d' % i: 'v' for i in range(200)}
    st, _, _ = request(port, 'GET', '/api/routes', headers=many)
    check(st == 431, '200 header fields: %s (431)' % st)
    st, _, _ = request(port, 'POST', '/api/feedback', b'x' * (3 * 1024 * 1024),
                       {'Content-Type': 'application/json'})
    check(st == 413, '3 MiB body with Content-Length: %s (413)' % st)
    st, _, _ = request(port, 'POST', '/api/routes', b'{}',
                       {'Content-Type': 'application/json', 'Transfer-Encoding': 'gzip, chunked'})
    check(st in (400, 501), 'Transfer-Encoding gzip, chunked: %s (400/501)' % st)
    # The editor's feedback: a 2 MiB body of 500,000 move lines is answered
    # at once with a refusal, no line read.
    crdl = 'name: x\n---\n' + 'R a b c d e f\n' * 125000
    t = time.monotonic()
    st, _, body = request(port, 'POST', '/api/feedback', json.dumps({'crdl': crdl}).encode(),
                          {'Content-Type': 'application/json'}, timeout=30)
    dt = time.monotonic() - t
    check(st == 200 and b'too long for live feedback' in body,
          'feedback of %d KiB: %s in %.2f s, refused as too long' % (len(crdl) // 1024, st, dt))


def slowloris(port, conns=300, seconds=12):
    """Many connections sending one header byte every 2 s from 127.0.0.2."""
    socks, refused = [], 0
    for _ in range(conns):
        try:
            s = connect(port, '127.0.0.2', timeout=3)
            s.sendall(b'GET / HTTP/1.1\r\nHost: x\r\n')
            socks.append(s)
        except OSError:
            refused += 1
    end = time.monotonic() + seconds
    closed_by_server = 0
    while time.monotonic() < end and socks:
        time.sleep(2)
        alive = []
        for s in socks:
            try:
                s.sendall(b'X')
                alive.append(s)
            except OSError:
                closed_by_server += 1
                s.close()
        socks = alive
    # Whatever is still open after the header deadline (10 s) was answered
    # (503 over the cap) or is being closed: check a few.
    answered = 0
    for s in socks:
        s.settimeout(0.5)
        try:
            data = s.recv(4096)
            if data == b'' or data.startswith(b'HTTP/1.1 503'):
                answered += 1
        except OSError:
            answered += 1
        s.close()
    check(closed_by_server + answered + refused >= conns - 5,
          'slowloris: %d connections, %d cut or refused by the server' %
          (conns, closed_by_server + answered + refused))


def logins(port):
    """64 parallel wrong guesses at the demo account from one address."""
    statuses = []
    lock = threading.Lock()

    def guess(i):
        body = json.dumps({'username': 'demo', 'password': 'wrong-%d' % i}).encode()
        try:
            st, _, _ = request(port, 'POST', '/api/sessions', body,
                               {'Content-Type': 'application/json'}, source='127.0.0.4',
                               timeout=30)
        except OSError:
            st = None
        with lock:
            statuses.append(st)

    ts = [threading.Thread(target=guess, args=(i,)) for i in range(64)]
    for t in ts:
        t.start()
    for t in ts:
        t.join()
    checked = statuses.count(401)
    check(checked <= 5 and checked + statuses.count(429) + statuses.count(503) == 64,
          '64 parallel log-in guesses: %d password checks (401), %d throttled (429), %d busy' %
          (checked, statuses.count(429), statuses.count(503)))


def costs(port):
    params = urllib.parse.quote(json.dumps({'skip': 100000}))
    t = time.monotonic()
    st, h, body = request(port, 'GET', '/api/landscape?grid=201&n=2000&params=' + params)
    dt = time.monotonic() - t
    check(st == 429 and dt < 1.0,
          'anonymous IC map grid 201, n 2000, skip 100000: %s in %.2f s (429 before work)' %
          (st, dt))
    # Maps under the per-request cap, each a new spacing (no cache), until
    # the per-address budget is spent: refused with Retry-After.
    got = []
    for i in range(40):
        st, h, body = request(port, 'GET', '/api/landscape?grid=61&n=500&spacing=0.%03d' %
                              (100 + i), source='127.0.0.6', timeout=30)
        got.append(st)
        if st == 429:
            check('retry-after' in h and int(h['retry-after']) > 0,
                  'spent map budget: 429 with Retry-After %s after %d maps' %
                  (h.get('retry-after'), i))
            break
    check(429 in got, 'a stream of uncached IC maps is stopped by the budget (%s)' % got[-3:])


def id_reuse(port):
    """A deleted route's id is never given to a new route."""
    login = json.dumps({'username': 'demo', 'password': 'strangebeta-demo'}).encode()
    st, h, body = request(port, 'POST', '/api/sessions', login,
                          {'Content-Type': 'application/json'}, source='127.0.0.7')
    check(st == 200, 'demo log-in: %s' % st)
    if st != 200:
        return
    cookie = h['set-cookie'].split(';')[0]
    csrf = json.loads(body)['csrf']
    auth = {'Content-Type': 'application/json', 'Cookie': cookie, 'X-CSRF-Token': csrf}
    route = json.dumps({'crdl': 'name: secret\n---\nR jug\nL crimp\n', 'public': False}).encode()
    st, _, body = request(port, 'POST', '/api/routes', route, auth)
    first = json.loads(body)['id']
    st, _, _ = request(port, 'DELETE', '/api/routes/%d' % first, headers=auth)
    st2, _, body = request(port, 'POST', '/api/routes', route, auth)
    second = json.loads(body)['id']
    check(st == 204 and second > first, 'ids not reused: deleted %d, next %d' % (first, second))


def hostile_import(port):
    """Imports rows that are valid but extreme (a 10,000-move route, a variation of it
    with max_repeat 1, markup in names) and views every page of each: never a 500, each
    view answered within 10 s. Rows the API refuses (nan, inf, 1e300) are refused with
    their file:line."""
    login = json.dumps({'username': 'demo', 'password': 'strangebeta-demo'}).encode()
    st, h, body = request(port, 'POST', '/api/sessions', login,
                          {'Content-Type': 'application/json'}, source='127.0.0.8')
    if st != 200:
        check(False, 'demo log-in for the import: %s' % st)
        return
    auth = {'Content-Type': 'application/json', 'Cookie': h['set-cookie'].split(';')[0],
            'X-CSRF-Token': json.loads(body)['csrf']}
    head = ('route_id,name,description,grade,is_variation,nna,dim_mask,max_repeat,transient,'
            'rx,ry,rz,vx,vy,vz,is_public\n')
    # Route 1: 10,000 moves and markup everywhere; route 4: 5,000 moves (the
    # most a variation may vary) and two variations of it, one with
    # max_repeat 1 and the longest transient, one with far-off ICs.
    routes = head + ('1,"<script>alert(1)</script> ""x""",desc </p>,V4,f,,,,,,,,,,,t\n'
                     '4,Long,,,f,,,,,,,,,,,t\n'
                     '2,Variation on 4,,,t,B,111,1,100000,-13,-12,52,-16,-12,52,t\n'
                     '3,"Variation on 4",,,t,D,011,1,0,50,-50,80,-16,-12,52,t\n')
    moves = 'route_id,seq_no,hand,move,crux\n' + ''.join(
        '%d,%d,%s,"move %d <b>&amp;</b>, ""q""",%s\n' % (r, i, 'RL'[i % 2], i, 'tf'[i % 7 != 0])
        for r, n in ((1, 10000), (4, 5000)) for i in range(1, n + 1))
    moves += '2,1,R,jug,f\n3,1,L,crimp,f\n'
    for bad, what in (('nan', 'not a finite number'), ('inf', 'not a finite number'),
                      ('1e300', 'diverged')):
        row = head + ('4,x,,,f,,,,,,,,,,,t\n'
                      '2,Variation on 4,,,t,B,111,1,0,%s,-12,52,-16,-12,52,t\n' % bad)
        st, _, body = request(port, 'POST', '/api/import/csv',
                              json.dumps({'routes_csv': row, 'moves_csv': moves}).encode(), auth,
                              timeout=60)
        check(st == 400 and b'routes.csv:3' in body and what.encode() in body,
              'import with rx=%s: %s %s' % (bad, st, body[:90]))
    t = time.monotonic()
    st, _, body = request(port, 'POST', '/api/import/csv',
                          json.dumps({'routes_csv': routes, 'moves_csv': moves}).encode(), auth,
                          timeout=60)
    check(st == 201, 'hostile but valid import: %s in %.1f s %s' %
          (st, time.monotonic() - t, body[:120]))
    if st != 201:
        return
    ids = sorted(json.loads(body)['ids'].values())
    worst = 0
    for i in ids:
        for path in ('/routes/%d', '/routes/%d/edit', '/variations/%d', '/variations/%d.pdf',
                     '/variations/%d.svg', '/api/routes/%d', '/api/routes/%d.crdl',
                     '/api/variations/%d', '/vary?routes=%d'):
            t = time.monotonic()
            st, _, _ = request(port, 'GET', path % i, headers={'Cookie': auth['Cookie']},
                               timeout=60)
            dt = time.monotonic() - t
            worst = max(worst, dt)
            check(st is not None and st < 500 and dt < 10,
                  'GET %s: %s in %.2f s' % (path % i, st, dt))
    print('     hostile import: worst page view %.2f s' % worst)


def main():
    build = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else 'build')
    source = os.path.abspath(sys.argv[2] if len(sys.argv) > 2 else
                             os.path.join(os.path.dirname(__file__), '..'))
    with tempfile.TemporaryDirectory() as tmp:
        server = Server(build, source, tmp)
        prober = Prober(server.port)
        prober.start()
        start = time.monotonic()
        try:
            attacks = [threading.Thread(target=slowloris, args=(server.port,))]
            for a in attacks:
                a.start()
            time.sleep(1)
            chunked_flood(server.port)
            refusals(server.port)
            logins(server.port)
            costs(server.port)
            id_reuse(server.port)
            hostile_import(server.port)
            for a in attacks:
                a.join()
        finally:
            time.sleep(0.3)
            prober.stop_flag.set()
            prober.join()
            peak = server.peak_rss_kb()
            rc = server.stop()
        lat = sorted(prober.latencies)
        worst = lat[-1] if lat else float('inf')
        check(not prober.bad and lat,
              'normal requests: %d, worst latency %.3f s, median %.3f s, over %.1f s (late or '
              'failed: %s)' % (len(lat), worst, lat[len(lat) // 2] if lat else 0,
                               time.monotonic() - start, prober.bad[:5]))
        check(peak < MAX_PEAK_RSS_KB, 'server peak memory %d MiB (< %d MiB)' %
              (peak // 1024, MAX_PEAK_RSS_KB // 1024))
        check(rc == 0, 'server stopped cleanly on SIGTERM (exit %s)' % rc)
        print('abuse: worst normal-request latency %.3f s' % worst)
    if failures:
        print('abuse.py: %d check(s) failed' % len(failures))
        return 1
    return 0


if __name__ == '__main__':
    sys.exit(main())
