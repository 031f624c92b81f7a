#!/usr/bin/python3
"""Two `strangebeta serve` processes over one PostgreSQL database (issue 17).

    tests/pg_two_servers.py BUILD_DIR SOURCE_DIR

Creates a fresh database on the test PostgreSQL server (the ctest fixture
`pg`, BUILD_DIR/pgtest/url; or a private server started with
scripts/pg_server.sh), starts two server processes on it (loopback, free
ports), and checks under a bounded concurrent load:

- no lost or duplicated writes: every route created through either process
  (WRITERS threads x ROUTES_PER_WRITER, alternating processes) is listed
  exactly once by both, with the id its 201 answer gave;
- no 5xx answer at all;
- sessions are valid on both: a session made on one process serves the
  other; a log-out on one ends it on the other;
- log-in throttling counts across both: concurrent wrong guesses spread over
  the two processes get exactly the free attempts (5) checked, the rest 429;
- private data is never served stale: a private route and variation made on
  one process are refused to others on the other, and gone on both once
  deleted;
- then, servers stopped, `strangebeta db copy` moves the database to a
  SQLite file and `db info` prints the same rows and checksums for both.

Exits 0 on success, 77 (ctest SKIP_RETURN_CODE) when PostgreSQL is not
installed, 1 with the failures listed otherwise.
"""

import json
import os
import re
import subprocess
import sys
import tempfile
import threading
import time
import urllib.error
import urllib.request

WRITERS = 8  # concurrent clients (bounded load)
ROUTES_PER_WRITER = 12
GUESSES = 16  # concurrent wrong passwords; 5 are free (app::LoginPolicy)
FREE_GUESSES = 5

failures = []


def fail(msg):
    failures.append(msg)
    print("FAIL: " + msg, file=sys.stderr)


def pg_bindir():
    root = "/usr/lib/postgresql"
    best = None
    if os.path.isdir(root):
        for v in sorted(os.listdir(root), key=lambda s: [int(x) for x in re.findall(r"\d+", s)]):
            b = os.path.join(root, v, "bin")
            if os.access(os.path.join(b, "initdb"), os.X_OK):
                best = b
    return best


class Http:
    """A client with one session cookie and its CSRF token."""

    def __init__(self, base):
        self.base = base
        self.cookie = ""
        self.csrf = ""

    def send(self, method, path, body=None):
        data = None if body is None else json.dumps(body).encode()
        req = urllib.request.Request(self.base + path, data=data, method=method)
        if data is not None:
            req.add_header("Content-Type", "application/json")
        if self.cookie:
            req.add_header("Cookie", self.cookie)
        if self.csrf:
            req.add_header("X-CSRF-Token", self.csrf)
        try:
            with urllib.request.urlopen(req, timeout=60) as r:
                status, headers, text = r.status, r.headers, r.read().decode()
        except urllib.error.HTTPError as e:
            status, headers, text = e.code, e.headers, e.read().decode()
        if status >= 500:
            fail(f"{method} {self.base}{path} -> {status}: {text[:200]}")
        return status, headers, text

    def log_in(self, user, password):
        status, headers, text = self.send("POST", "/api/sessions",
                                          {"username": user, "password": password})
        if status == 200:
            self.cookie = headers.get("Set-Cookie", "").split(";")[0]
            self.csrf = json.loads(text)["csrf"]
        return status


def start_server(build, url, log):
    p = subprocess.Popen([os.path.join(build, "strangebeta"), "serve", "--port", "0", "--db", url,
                          "--no-seed", "--threads", "8", "--db-pool", "4"],
                         stdout=log, stderr=subprocess.STDOUT)
    for _ in range(300):
        with open(log.name) as f:
            m = re.search(r"http://127\.0\.0\.1:(\d+)/", f.read())
        if m:
            return p, f"http://127.0.0.1:{m.group(1)}"
        if p.poll() is not None:
            break
        time.sleep(0.1)
    with open(log.name) as f:
        sys.exit("server did not start:\n" + f.read())


def main():
    build, source = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    bindir = pg_bindir()
    if not bindir:
        print("SKIP: PostgreSQL binaries are absent (/usr/lib/postgresql/*/bin; Debian package "
              "postgresql)")
        return 77
    tmp = tempfile.mkdtemp(prefix="sb_two_")
    private = None
    admin = ""
    try:
        with open(os.path.join(build, "pgtest", "url")) as f:
            admin = f.readline().strip()
    except OSError:
        pass
    psql = os.path.join(bindir, "psql")
    if not admin or subprocess.run([psql, admin, "-Atc", "SELECT 1"],
                                   capture_output=True).returncode != 0:
        private = os.path.join(tmp, "pg")
        subprocess.run(["bash", os.path.join(source, "scripts", "pg_server.sh"), "start", private],
                       check=True)
        with open(os.path.join(private, "url")) as f:
            admin = f.readline().strip()
    name = f"sb_two_{os.getpid()}"
    url = admin.rsplit("/", 1)[0] + "/" + name
    subprocess.run([psql, admin, "-qc", f"CREATE DATABASE {name}"], check=True)
    servers = []
    try:
        logs = [open(os.path.join(tmp, f"serve{i}.log"), "w+") for i in range(2)]
        # The first process migrates; the second finds the schema in place.
        servers.append(start_server(build, url, logs[0]))
        servers.append(start_server(build, url, logs[1]))
        a, b = servers[0][1], servers[1][1]
        run_checks(a, b)
        for p, _ in servers:
            p.terminate()
            p.wait(timeout=30)
        servers = []
        check_copy(build, url, os.path.join(tmp, "copy.db"))
    finally:
        for p, _ in servers:
            p.terminate()
            p.wait(timeout=30)
        subprocess.run([psql, admin, "-qc", f"DROP DATABASE IF EXISTS {name} WITH (FORCE)"])
        if private:
            subprocess.run(["bash", os.path.join(source, "scripts", "pg_server.sh"), "stop",
                            private])
        subprocess.run(["rm", "-rf", tmp])
    if failures:
        print(f"{len(failures)} failure(s)", file=sys.stderr)
        return 1
    print("two servers on one PostgreSQL database: all checks passed")
    return 0


def check_copy(build, url, path):
    exe = os.path.join(build, "strangebeta")
    r = subprocess.run([exe, "db", "copy", "--from", url, "--to", path], capture_output=True,
                       text=True)
    if r.returncode != 0:
        fail(f"db copy to SQLite: exit {r.returncode}: {r.stderr}")
        return
    tables = {}
    for db in (url, path):
        r = subprocess.run([exe, "db", "info", "--db", db], capture_output=True, text=True)
        if r.returncode != 0:
            fail(f"db info {db}: {r.stderr}")
            return
        # "table  rows  checksum  next id" lines after the header.
        lines = r.stdout.splitlines()
        start = next(i for i, l in enumerate(lines) if l.startswith("table")) + 1
        tables[db] = [l.split()[:3] for l in lines[start:]]
    if tables[url] != tables[path]:
        fail(f"db info differs after the copy: {tables[url]} vs {tables[path]}")
    routes = [t for t in tables[url] if t[0] == "routes"]
    if not routes or int(routes[0][1]) < WRITERS * ROUTES_PER_WRITER:
        fail(f"db info routes: {routes}")


def run_checks(a, b):
    # Sessions: sign up on A, log in on A, use the session on B.
    owner = Http(a)
    if owner.send("POST", "/api/users", {"username": "alice", "password": "password123"})[0] != 201:
        fail("sign-up on A")
    if owner.log_in("alice", "password123") != 200:
        fail("log-in on A")
    on_b = Http(b)
    on_b.cookie, on_b.csrf = owner.cookie, owner.csrf
    st, _, text = on_b.send("GET", "/api/session")
    if st != 200 or json.loads(text).get("username") != "alice":
        fail(f"a session made on A is not valid on B: {st} {text[:100]}")

    # Concurrent writes through both processes.
    writers = []
    for i in range(WRITERS):
        c = Http(a if i % 2 == 0 else b)
        c.cookie, c.csrf = owner.cookie, owner.csrf
        writers.append(c)
    created = [[] for _ in range(WRITERS)]

    def write(i):
        for j in range(ROUTES_PER_WRITER):
            c = writers[i]
            c.base = a if (i + j) % 2 == 0 else b
            name = f"w{i}-r{j}"
            crdl = f"name: {name}\n---\nR jug\nL crimp\nR sloper\n"
            st, _, text = c.send("POST", "/api/routes", {"crdl": crdl, "public": True})
            if st == 201:
                created[i].append((json.loads(text)["id"], name))
            else:
                fail(f"POST /api/routes {name} -> {st}: {text[:100]}")

    threads = [threading.Thread(target=write, args=(i,)) for i in range(WRITERS)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    want = sorted(x for w in created for x in w)
    ids = [i for i, _ in want]
    if len(set(ids)) != len(ids):
        fail("two writes answered with the same id")
    if len(want) != WRITERS * ROUTES_PER_WRITER:
        fail(f"{len(want)} routes created, {WRITERS * ROUTES_PER_WRITER} expected")
    for base in (a, b):
        st, _, text = Http(base).send("GET", "/api/routes?limit=5000")
        got = sorted((r["id"], r["name"]) for r in json.loads(text)["routes"])
        if got != want:
            fail(f"{base} lists {len(got)} routes, {len(want)} were written (lost or duplicated)")

    # Private data made on A is never shown to others on B, and is gone on
    # both once deleted on A.
    st, _, text = owner.send("POST", "/api/routes", {
        "crdl": "name: secret\n---\nR jug\nL crimp\nR sloper\nL pinch\n", "public": False})
    secret = json.loads(text)["id"]
    st, _, text = owner.send("POST", "/api/variations", {"routes": [secret], "public": False})
    if st != 201:
        fail(f"private variation on A -> {st}: {text[:200]}")
        return
    var = json.loads(text)["id"]
    anon_b = Http(b)
    for path in (f"/api/routes/{secret}", f"/api/variations/{var}"):
        if on_b.send("GET", path)[0] != 200:
            fail(f"the owner cannot read {path} on B")
        if anon_b.send("GET", path)[0] != 404:
            fail(f"a stranger can read private {path} on B")
    if owner.send("DELETE", f"/api/routes/{var}")[0] not in (200, 204):
        fail("delete of the variation on A")
    for base in (a, b):
        c = Http(base)
        c.cookie, c.csrf = owner.cookie, owner.csrf
        st = c.send("GET", f"/api/variations/{var}")[0]
        if st != 404:
            fail(f"a deleted variation still answers {st} on {base}")

    # A public variation of a public route, read by a stranger on B (its plan
    # now cached there); the owner makes both private on A: B must refuse
    # both at once (its cache is keyed by content and checked against a
    # fresh read).
    st, _, text = owner.send("POST", "/api/routes", {
        "crdl": "name: shown\n---\nR jug\nL crimp\nR sloper\nL pinch\n", "public": True})
    shown = json.loads(text)["id"]
    st, _, text = owner.send("POST", "/api/variations", {"routes": [shown], "public": True})
    shown_var = json.loads(text)["id"]
    for path in (f"/api/routes/{shown}", f"/api/variations/{shown_var}"):
        if anon_b.send("GET", path)[0] != 200:
            fail(f"a stranger cannot read public {path} on B")
    for rid in (shown, shown_var):
        if owner.send("PUT", f"/api/routes/{rid}", {"public": False})[0] != 200:
            fail(f"making {rid} private on A")
    for path in (f"/api/routes/{shown}", f"/api/variations/{shown_var}"):
        st = anon_b.send("GET", path)[0]
        if st != 404:
            fail(f"{path} made private on A still answers {st} to a stranger on B")

    # Throttling across processes: concurrent wrong guesses over A and B.
    results = []
    lock = threading.Lock()

    def guess(i):
        st = Http(a if i % 2 == 0 else b).log_in("alice", "wrong-password")
        with lock:
            results.append(st)

    threads = [threading.Thread(target=guess, args=(i,)) for i in range(GUESSES)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    checked = results.count(401)
    refused = results.count(429)
    if checked != FREE_GUESSES or refused != GUESSES - FREE_GUESSES:
        fail(f"{GUESSES} concurrent wrong guesses over both processes: {checked} checked "
             f"(401), {refused} refused (429); expected {FREE_GUESSES} and "
             f"{GUESSES - FREE_GUESSES}: {sorted(results)}")

    # A log-out on B ends the session on A too.
    if on_b.send("DELETE", "/api/sessions")[0] not in (200, 204):
        fail("log-out on B")
    if owner.send("GET", "/api/session")[0] == 200 and \
            json.loads(owner.send("GET", "/api/session")[2]).get("username") == "alice":
        fail("a session ended on B is still valid on A")


if __name__ == "__main__":
    sys.exit(main())
