#!/usr/bin/env python3
"""A busy gym's evening (issue 34, docs/BENCHMARKS.md "A busy gym"): one server of a
synthetic gym (`strangebeta synth`: head-1, setters setter-1-K, password
synth-chain-password) under this load at once, each client from loopback addresses of its
own (127.0.x.y, so the per-address limits see separate clients):

  phones      8 phones (device cookies, one address each) ticking a route on the wall once a second
  tickers     8 addresses ticking back to back (a fresh device each time)
  reports     4 members (setter-1-2..5) reading /api/gyms/1/report?date=... back to back
  sheets      16 anonymous addresses printing tag sheets (/tags.pdf?ids=..., costed) back to back
  throwaway   8 throw-away gyms (made at the start by 8 accounts); 8 anonymous readers of their
              route pages, ascents and wall pages, back to back
  setter      setter-1-1 loading a route page, a wall page and the dashboard every half second,
              and the gym's tag sheet of a wall (the setter's own costed work) every 2 s

It prints the setter's p50/p99 per page, every kind's answers by status, failed requests
(5xx, connection errors, timeouts; 429 with Retry-After is a refusal, counted apart), the
server's RSS (VmRSS) idle after warm-up and its peak (VmHWM) against 2x idle when it knows
the server's pid, and whether the setter's costed work was served. Python stdlib only.

  bench/busy_gym.py --url http://127.0.0.1:PORT --pid PID --seconds 60
  bench/busy_gym.py ... --json out.json      # the figures as JSON too
  bench/busy_gym.py ... --scale 0.25         # a quarter of every crowd (the short load test)

tests/load.py (CTest `load`) runs it for a few seconds on a small synthetic gym.
"""
import argparse
import http.client
import json
import random
import re
import sys
import threading
import time
import urllib.parse

PASSWORD = 'synth-chain-password'


class Client:
    """One keep-alive connection from one source address, with a cookie jar of one."""

    def __init__(self, host, port, src, timeout=30):
        self.host, self.port, self.src, self.timeout = host, port, src, timeout
        self.conn = None
        self.cookies = {}
        self.csrf = ''

    def request(self, method, path, body=None):
        headers = {'Content-Type': 'application/json'} if body is not None else {}
        if self.cookies:
            headers['Cookie'] = '; '.join('%s=%s' % kv for kv in self.cookies.items())
        if self.csrf:
            headers['X-CSRF-Token'] = self.csrf
        data = json.dumps(body).encode() if body is not None else None
        for attempt in range(2):
            if self.conn is None:
                self.conn = http.client.HTTPConnection(self.host, self.port, timeout=self.timeout,
                                                       source_address=(self.src, 0))
            try:
                self.conn.request(method, path, body=data, headers=headers)
                r = self.conn.getresponse()
                payload = r.read()
                for h, v in r.getheaders():
                    if h.lower() == 'set-cookie':
                        name, _, rest = v.partition('=')
                        self.cookies[name.strip()] = rest.split(';')[0]
                if r.getheader('connection', '').lower() == 'close':
                    self.close()
                return r.status, r.getheader('retry-after'), payload
            except (http.client.RemoteDisconnected, BrokenPipeError, ConnectionResetError):
                # A kept-alive connection the server closed between requests: once more.
                self.close()
                if attempt == 1:
                    raise
        raise OSError('unreachable')

    def close(self):
        if self.conn is not None:
            self.conn.close()
            self.conn = None

    def sign_in(self, username, password=PASSWORD):
        st, _, body = self.request('POST', '/api/sessions',
                                   {'username': username, 'password': password})
        if st != 200:
            raise SystemExit('busy_gym.py: cannot sign in %s: %d %s' % (username, st, body[:200]))
        self.csrf = json.loads(body)['csrf']


class Stats:
    def __init__(self):
        self.lock = threading.Lock()
        self.by_kind = {}  # kind -> {'n', 'status': {code: n}, 'lat': [s], 'failed', 'retry_missing'}

    def add(self, kind, status, retry_after, seconds):
        with self.lock:
            k = self.by_kind.setdefault(kind, {'n': 0, 'status': {}, 'lat': [], 'failed': 0,
                                               'retry_missing': 0})
            k['n'] += 1
            k['status'][str(status)] = k['status'].get(str(status), 0) + 1
            k['lat'].append(seconds)
            if not isinstance(status, int) or status >= 500:  # 2xx-4xx are answers
                k['failed'] += 1
            if status == 429 and not retry_after:
                k['retry_missing'] += 1


def pct(values, p):
    if not values:
        return float('nan')
    v = sorted(values)
    return v[min(len(v) - 1, int(round(p / 100.0 * (len(v) - 1))))]


def rss_kb(pid, field):
    try:
        with open('/proc/%d/status' % pid) as f:
            for line in f:
                if line.startswith(field + ':'):
                    return int(line.split()[1])
    except OSError:
        pass
    return 0


def timed(stats, kind, client, method, path, body=None):
    t = time.monotonic()
    try:
        status, retry, payload = client.request(method, path, body)
    except (OSError, http.client.HTTPException) as e:
        client.close()
        status, retry, payload = 'error: %s' % type(e).__name__, None, b''
    stats.add(kind, status, retry, time.monotonic() - t)
    return status, payload


def setup(host, port, rng, log):
    """Finds the gym's routes, walls and report dates; makes the throw-away gyms."""
    head = Client(host, port, '127.0.9.1')
    head.sign_in('head-1')
    st, _, body = head.request('GET', '/api/routes?gym=1&state=set&limit=500')
    on_wall = [r['id'] for r in json.loads(body)['routes']]
    st, _, body = head.request('GET', '/api/gyms/1/walls')
    walls = [w['id'] for w in json.loads(body)['walls']]
    # Setting days of the gym with routes (the reports' dates).
    dates = {}
    st, _, body = head.request('GET', '/api/routes?gym=1&state=stripped&limit=500&sort=newest')
    for r in json.loads(body)['routes']:
        d = r.get('set_on') or ''
        if re.match(r'^\d{4}-\d{2}-\d{2}$', d):
            dates[d] = dates.get(d, 0) + 1
    report_dates = [d for d, n in sorted(dates.items(), key=lambda kv: -kv[1])[:8]] or ['2026-01-01']
    if not on_wall or not walls:
        raise SystemExit('busy_gym.py: gym 1 has no routes on the wall or no walls')
    # Throw-away gyms: an account each (from its own address: sign-ups are limited per
    # address), a wall, two routes set and in the library, a tick on each.
    throwaway = []  # (route ids, wall id)
    for i in range(8):
        c = Client(host, port, '127.0.8.%d' % (i + 1))
        name = 'throwaway%d%d' % (i, rng.randrange(10 ** 6))
        c.request('POST', '/api/users', {'username': name, 'password': PASSWORD})
        c.sign_in(name)
        st, _, body = c.request('POST', '/api/gyms', {'name': 'Throwaway ' + name})
        if st != 201:
            log('throw-away gym %d: %d %s' % (i, st, body[:120]))
            continue
        g = json.loads(body)['id']
        st, _, body = c.request('POST', '/api/gyms/%d/walls' % g, {'name': 'Wall'})
        w = json.loads(body)['id']
        ids = []
        for k in range(2):
            crdl = ('name: Tossed %d-%d\ngrade: V%d\ncolour: red\n---\nR small crimp\n'
                    'L heel hook the arete\nR jug\n' % (i, k, 2 + k))
            st, _, body = c.request('POST', '/api/routes', {
                'crdl': crdl, 'library': True, 'gym': g, 'wall': 'Wall', 'state': 'set',
                'set_on': '2026-11-20'})
            if st == 201:
                ids.append(json.loads(body)['id'])
        for rid in ids:
            c.request('POST', '/api/routes/%d/ticks' % rid, {'outcome': 'send', 'attempts': 2})
        c.close()
        throwaway.append((ids, w))
    head.close()
    return on_wall, walls, report_dates, throwaway


def run(args):
    u = urllib.parse.urlparse(args.url)
    host, port = u.hostname, u.port
    rng = random.Random(args.seed)
    out = sys.stderr if args.json == '-' else sys.stdout

    def log(s):
        print(s, file=out, flush=True)

    on_wall, walls, dates, throwaway = setup(host, port, rng, log)
    library = [i for ids, _ in throwaway for i in ids]
    setter = Client(host, port, '127.0.4.1')
    setter.sign_in('setter-1-1')
    route_page = '/routes/%d' % on_wall[0]
    wall_page = '/walls/%d' % walls[0]
    dash_page = '/gyms/1/dashboard'
    sheet = '/api/gyms/1/tags.pdf?wall=%d' % walls[1 % len(walls)]
    # Warm-up: the gym's fit, the kept pages, one report.
    t = time.monotonic()
    for p in (route_page, wall_page, dash_page, wall_page, dash_page):
        st, _, _ = setter.request('GET', p)
        if st != 200:
            raise SystemExit('busy_gym.py: warm-up %s answered %d' % (p, st))
    setter.request('GET', '/api/gyms/1/report?date=' + dates[0])
    log('warm-up %.1f s' % (time.monotonic() - t))
    time.sleep(1.0)
    idle_kb = rss_kb(args.pid, 'VmRSS') if args.pid else 0

    stats = Stats()
    stop = threading.Event()
    deadline = time.monotonic() + args.seconds

    def n(count):
        return max(1, int(round(count * args.scale)))

    def phone(i):
        c = Client(host, port, '127.0.1.%d' % (i + 1))
        r = random.Random(args.seed * 100 + i)
        while not stop.is_set():
            t0 = time.monotonic()
            timed(stats, 'phone tick', c, 'POST', '/api/routes/%d/ticks' % r.choice(on_wall),
                  {'outcome': r.choice(['flash', 'send', 'attempt']), 'attempts': 1})
            stop.wait(max(0.0, 1.0 - (time.monotonic() - t0)))

    def ticker(i):
        c = Client(host, port, '127.0.2.%d' % (i + 1))
        r = random.Random(args.seed * 200 + i)
        while not stop.is_set():
            c.cookies.clear()  # a fresh device each time
            timed(stats, 'ticker tick', c, 'POST', '/api/routes/%d/ticks' % r.choice(on_wall),
                  {'outcome': 'send', 'attempts': 1})

    def reader(i):
        c = Client(host, port, '127.0.3.%d' % (i + 1))
        c.sign_in('setter-1-%d' % (i + 2))
        r = random.Random(args.seed * 300 + i)
        while not stop.is_set():
            timed(stats, 'member report', c, 'GET', '/api/gyms/1/report?date=' + r.choice(dates))

    def printer(i):
        c = Client(host, port, '127.0.5.%d' % (i + 1))
        r = random.Random(args.seed * 400 + i)
        while not stop.is_set():
            ids = [r.choice(library) for _ in range(8)] if library else [on_wall[0]]
            timed(stats, 'anonymous sheet', c, 'GET', '/tags.pdf?ids=' + ','.join(map(str, ids)))

    def outsider(i):
        c = Client(host, port, '127.0.6.%d' % (i + 1))
        ids, w = throwaway[i % len(throwaway)] if throwaway else ([on_wall[0]], walls[0])
        k = 0
        while not stop.is_set():
            rid = ids[k % len(ids)] if ids else on_wall[0]
            path = ['/api/routes/%d/ascent' % rid, '/r/%d' % rid, '/walls/%d' % w][k % 3]
            timed(stats, 'throw-away reader', c, 'GET', path)
            k += 1

    def the_setter():
        k = 0
        next_sheet = time.monotonic()
        while not stop.is_set():
            t0 = time.monotonic()
            for kind, p in (('setter route page', route_page), ('setter wall page', wall_page),
                            ('setter dashboard', dash_page)):
                timed(stats, kind, setter, 'GET', p)
            if time.monotonic() >= next_sheet:
                timed(stats, 'setter costed sheet', setter, 'GET', sheet)
                next_sheet += 2.0
            k += 1
            stop.wait(max(0.0, 0.5 - (time.monotonic() - t0)))

    threads = []
    for count, fn in ((8, phone), (8, ticker), (4, reader), (16, printer), (8, outsider)):
        for i in range(n(count)):
            threads.append(threading.Thread(target=fn, args=(i,), daemon=True))
    threads.append(threading.Thread(target=the_setter, daemon=True))
    for th in threads:
        th.start()
    peak_rss = 0
    while time.monotonic() < deadline:
        time.sleep(0.25)
        if args.pid:
            peak_rss = max(peak_rss, rss_kb(args.pid, 'VmRSS'))
    stop.set()
    for th in threads:
        th.join(timeout=60)

    result = {'seconds': args.seconds, 'scale': args.scale, 'idle_rss_kb': idle_kb,
              'peak_rss_kb': peak_rss, 'kinds': {}}
    failed = 0
    for kind, k in sorted(stats.by_kind.items()):
        result['kinds'][kind] = {'n': k['n'], 'status': k['status'],
                                 'p50_ms': round(1000 * pct(k['lat'], 50), 1),
                                 'p99_ms': round(1000 * pct(k['lat'], 99), 1),
                                 'max_ms': round(1000 * max(k['lat']), 1),
                                 'failed': k['failed'], 'retry_after_missing': k['retry_missing']}
        failed += k['failed']
    setter_lat = [x for kind, k in stats.by_kind.items() if kind.startswith('setter ')
                  and kind != 'setter costed sheet' for x in k['lat']]
    result['setter_pages'] = {'n': len(setter_lat),
                              'p50_ms': round(1000 * pct(setter_lat, 50), 1),
                              'p99_ms': round(1000 * pct(setter_lat, 99), 1)}
    setter_bad = sum(n for kind, k in stats.by_kind.items() if kind.startswith('setter ')
                     for code, n in k['status'].items() if code != '200')
    sheet = stats.by_kind.get('setter costed sheet', {'status': {}})
    result['failed'] = failed
    result['setter_not_200'] = setter_bad
    result['setter_costed_served'] = sheet['status'].get('200', 0)
    result['setter_costed_asked'] = sum(sheet['status'].values())
    result['retry_after_missing'] = sum(k['retry_missing'] for k in stats.by_kind.values())

    log('%-20s %7s %9s %9s %9s  %s' % ('kind', 'n', 'p50 ms', 'p99 ms', 'max ms', 'answers'))
    for kind, k in result['kinds'].items():
        log('%-20s %7d %9.1f %9.1f %9.1f  %s' % (kind, k['n'], k['p50_ms'], k['p99_ms'],
                                                 k['max_ms'], json.dumps(k['status'])))
    log('setter pages: n %d, p50 %.1f ms, p99 %.1f ms; not 200: %d; costed sheet served %d of %d'
        % (result['setter_pages']['n'], result['setter_pages']['p50_ms'],
           result['setter_pages']['p99_ms'], setter_bad, result['setter_costed_served'],
           result['setter_costed_asked']))
    log('failed requests (5xx, errors): %d; 429 without Retry-After: %d'
        % (failed, result['retry_after_missing']))
    if args.pid:
        log('server RSS: idle %.0f MiB, peak during the load %.0f MiB (%.2fx idle)'
            % (idle_kb / 1024, peak_rss / 1024, peak_rss / max(1, idle_kb)))
    if args.json:
        text = json.dumps(result, indent=1, sort_keys=True)
        if args.json == '-':
            print(text)
        else:
            with open(args.json, 'w') as f:
                f.write(text + '\n')
    return result


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--url', required=True)
    ap.add_argument('--pid', type=int, default=0, help="the server's pid (its memory)")
    ap.add_argument('--seconds', type=float, default=60)
    ap.add_argument('--scale', type=float, default=1.0, help='share of every crowd (min 1 each)')
    ap.add_argument('--seed', type=int, default=1)
    ap.add_argument('--json', default='', help="write the figures to this file ('-': stdout)")
    args = ap.parse_args(argv)
    return run(args)


if __name__ == '__main__':
    main()
