#!/usr/bin/env python3
"""The short load test of issue 34 (CTest `load`, Release builds only; the long one is
bench/busy_gym.py, docs/BENCHMARKS.md "A busy gym").

Makes a small synthetic gym (`strangebeta synth`: 1 gym, 10 walls, 20,000 ticks), starts
the server on it and runs bench/busy_gym.py for a few seconds with every crowd of the
benchmark (phones, back-to-back tickers, members reading reports, anonymous sheet printers,
readers of throw-away gyms) beside a setter. It checks what must hold whatever the
machine's speed:
  - no request failed (no 5xx, no connection error or timeout), from anyone;
  - every request of the setter (route page, wall page, dashboard) answered 200, and the
    setter's own costed work (the gym's tag sheet of a wall) was served every time although
    anonymous printers fill their share of the costly slots;
  - every refusal (429) says when to come back (Retry-After);
  - the anonymous printers were refused some of the time (the flood is real);
  - the server's peak memory stayed under 2x its idle size plus 64 MiB.
Latencies are printed, not checked (performance is a benchmark: docs/BENCHMARKS.md).

  tests/load.py BUILD_DIR SOURCE_DIR [SECONDS]
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

build, source = sys.argv[1], sys.argv[2]
seconds = float(sys.argv[3]) if len(sys.argv) > 3 else 8
sys.path.insert(0, os.path.join(source, 'bench'))
import busy_gym  # noqa: E402

binary = os.path.join(build, 'strangebeta')
tmp = tempfile.mkdtemp(prefix='sb-load-')
failures = []


def check(cond, what):
    print(('ok   ' if cond else 'FAIL ') + what, flush=True)
    if not cond:
        failures.append(what)


proc = None
try:
    db = os.path.join(tmp, 'gym.db')
    t = time.monotonic()
    subprocess.run([binary, 'synth', '--db', db, '--gyms', '1', '--walls', '10', '--on-wall',
                    '100', '--archived', '1000', '--ticks', '20000', '--climbers', '300',
                    '--today', '2026-11-26', '--fast-hash', '--quiet'], check=True)
    print('synth: %.1f s' % (time.monotonic() - t), flush=True)
    log = open(os.path.join(tmp, 'server.log'), 'w+')
    proc = subprocess.Popen([binary, 'serve', '--port', '0', '--db', db, '--no-seed'],
                            stdout=log, stderr=subprocess.STDOUT)
    port = None
    for _ in range(300):
        log.seek(0)
        m = re.search(r'http://127\.0\.0\.1:(\d+)/', log.read())
        if m:
            port = int(m.group(1))
            break
        time.sleep(0.1)
    if port is None:
        log.seek(0)
        raise SystemExit('load.py: the server did not start:\n' + log.read()[-2000:])
    r = busy_gym.main(['--url', 'http://127.0.0.1:%d' % port, '--pid', str(proc.pid),
                       '--seconds', str(seconds), '--scale', '0.5'])
    check(proc.poll() is None, 'the server is still running')
    check(r['failed'] == 0, 'no failed request (5xx, errors): %d' % r['failed'])
    check(r['setter_not_200'] == 0,
          "every setter's request answered 200 (not: %d)" % r['setter_not_200'])
    check(r['setter_costed_asked'] > 0 and
          r['setter_costed_served'] == r['setter_costed_asked'],
          "the setter's costed sheet served %d of %d times" % (r['setter_costed_served'],
                                                               r['setter_costed_asked']))
    check(r['retry_after_missing'] == 0,
          'every 429 has Retry-After (missing: %d)' % r['retry_after_missing'])
    sheets = r['kinds'].get('anonymous sheet', {'status': {}})['status']
    check(sheets.get('429', 0) > 0,
          'anonymous printers were refused (429) some of the time: %s' % sheets)
    check(r['kinds'].get('member report', {'status': {}})['status'].get('200', 0) > 0,
          'members read reports')
    limit = 2 * r['idle_rss_kb'] + 64 * 1024
    check(0 < r['peak_rss_kb'] < limit, 'peak RSS %d KiB < 2 x idle %d KiB + 64 MiB'
          % (r['peak_rss_kb'], r['idle_rss_kb']))
finally:
    if proc is not None:
        proc.terminate()
        try:
            proc.wait(10)
        except subprocess.TimeoutExpired:
            proc.kill()
    shutil.rmtree(tmp, ignore_errors=True)

if failures:
    print('load.py: %d check(s) failed' % len(failures))
    sys.exit(1)
print('load.py: all checks passed')
