#!/usr/bin/env bash
# A throw-away PostgreSQL server for the tests, from Debian's postgresql
# package (initdb + pg_ctl from /usr/lib/postgresql/*/bin, never a PATH
# symlink), in a temporary directory on a free loopback port.
#
#   scripts/pg_server.sh start STATE_DIR   start one; writes STATE_DIR/url (an
#                                         admin URL: user sb, database postgres)
#   scripts/pg_server.sh stop STATE_DIR    stop it and remove its data
#
# As root the server runs as the system user sbpgtest (created here when
# absent): PostgreSQL refuses to run as root. Listens on 127.0.0.1 only, with
# trust authentication for that address (nothing else can reach it) and no
# durability (fsync off: the data is thrown away). When the binaries are
# absent, `start` says so and exits 0 without a URL: the tests then skip.
# ctest runs `start` as the fixture pg_server_start and `stop` as
# pg_server_stop (tests/CMakeLists.txt).
set -euo pipefail
cmd=${1:-}
state=${2:-}
[[ "$cmd" == start || "$cmd" == stop ]] && [[ -n "$state" ]] ||
  { echo "usage: $0 start|stop STATE_DIR" >&2; exit 2; }
pg_user=sbpgtest

bindir=""
for d in $(ls -d /usr/lib/postgresql/*/bin 2>/dev/null | sort -V); do
  [[ -x "$d/initdb" && -x "$d/pg_ctl" ]] && bindir=$d
done

as_pg() {
  if [[ $(id -u) -eq 0 ]]; then runuser -u "$pg_user" -- "$@"; else "$@"; fi
}

stop() {
  [[ -f "$state/data_dir" ]] || return 0
  local tmp
  tmp=$(cat "$state/data_dir")
  if [[ -n "$bindir" && -f "$tmp/data/postmaster.pid" ]]; then
    as_pg "$bindir/pg_ctl" -D "$tmp/data" -m immediate -w stop >/dev/null 2>&1 || true
  fi
  rm -rf "$tmp"
  rm -f "$state/data_dir" "$state/url"
}

if [[ "$cmd" == stop ]]; then
  stop
  exit 0
fi

mkdir -p "$state"
stop  # a server left by an earlier run
if [[ -z "$bindir" ]]; then
  echo "pg_server.sh: PostgreSQL binaries absent (/usr/lib/postgresql/*/bin/initdb; Debian package" \
       "postgresql): tests on PostgreSQL will skip"
  exit 0
fi
if [[ $(id -u) -eq 0 ]] && ! id -u "$pg_user" >/dev/null 2>&1; then
  useradd --system --no-create-home --home-dir /nonexistent --shell /usr/sbin/nologin "$pg_user"
fi

tmp=$(mktemp -d "${TMPDIR:-/tmp}/sb_pg.XXXXXX")
echo "$tmp" >"$state/data_dir"
[[ $(id -u) -eq 0 ]] && chown "$pg_user" "$tmp"
chmod 700 "$tmp"
as_pg "$bindir/initdb" -D "$tmp/data" -U sb --auth=trust --encoding=UTF8 --locale=C.UTF-8 -N \
  >"$tmp/initdb.log" 2>&1 || { cat "$tmp/initdb.log" >&2; stop; exit 1; }

free_port() {
  /usr/bin/python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'
}
for attempt in 1 2 3 4 5; do
  port=$(free_port)
  if as_pg "$bindir/pg_ctl" -D "$tmp/data" -l "$tmp/server.log" -w -t 60 \
      -o "-p $port -k $tmp -c listen_addresses=127.0.0.1 -c fsync=off -c synchronous_commit=off \
          -c full_page_writes=off -c max_connections=300 -c shared_buffers=32MB" \
      start >/dev/null 2>&1; then
    echo "postgresql://sb@127.0.0.1:$port/postgres" >"$state/url"
    echo "pg_server.sh: PostgreSQL $("$bindir/postgres" --version | awk '{print $3}') on" \
         "127.0.0.1:$port (data in $tmp)"
    exit 0
  fi
  # The port was taken between the probe and the start: try another.
  tail -3 "$tmp/server.log" >&2 || true
done
echo "pg_server.sh: could not start PostgreSQL (log: $tmp/server.log)" >&2
cat "$tmp/server.log" >&2 || true
stop
exit 1
