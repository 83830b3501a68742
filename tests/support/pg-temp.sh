# A throw-away PostgreSQL server with PostGIS for a test: its own cluster in a temporary folder,
# reachable only through a Unix socket there (no TCP port to collide with), trust authentication.
# Source this file, then:  url=$(pg_temp_start DIR)  ...  pg_temp_stop DIR
# The server refuses to run as root, so as root it runs as Debian's `postgres` user.

pg_temp_bin() { ls -d /usr/lib/postgresql/*/bin 2>/dev/null | sort -V | tail -n 1; }

pg_temp_as() {
  if [[ $(id -u) -eq 0 ]]; then runuser -u postgres -- "$@"; else "$@"; fi
}

# Prints the URL of a fresh database "roadload" in a cluster under DIR (created).
pg_temp_start() {
  local dir=$1 bin
  bin=$(pg_temp_bin)
  [[ -x $bin/initdb ]] || { echo "pg_temp_start: no PostgreSQL server (Debian: postgresql, postgis)" >&2; return 77; }
  mkdir -p "$dir"
  if [[ $(id -u) -eq 0 ]]; then chown postgres: "$dir"; fi
  pg_temp_as "$bin/initdb" -D "$dir/data" -A trust -U postgres --no-sync >"$dir/initdb.log" 2>&1 ||
    { cat "$dir/initdb.log" >&2; return 1; }
  pg_temp_as "$bin/pg_ctl" -D "$dir/data" -l "$dir/server.log" -w -t 60 \
    -o "-c listen_addresses='' -c unix_socket_directories='$dir' -c fsync=off -c full_page_writes=off" start >/dev/null ||
    { cat "$dir/server.log" >&2; return 1; }
  pg_temp_as "$bin/createdb" -h "$dir" -U postgres roadload || return 1
  echo "postgresql:///roadload?host=$dir&user=postgres"
}

pg_temp_stop() {
  local dir=$1 bin
  bin=$(pg_temp_bin)
  [[ -d $dir/data ]] && pg_temp_as "$bin/pg_ctl" -D "$dir/data" -m immediate -w stop >/dev/null 2>&1
  rm -rf "$dir"
}
