#!/usr/bin/env bash
# A ShadeLab cluster on this machine, in the foreground: Redis (the shared store), N replicas of
# `shadelab serve`, and nginx in front of them (deploy/nginx/shadelab.conf.template). A replica
# that dies is started again on its port, as Kubernetes would; Ctrl-C or SIGTERM stops them all.
#
#   tools/cluster.sh [--replicas N] [--port P] [--host H] [--workers W] [--dir DIR] [-- SERVE FLAGS...]
#
# DIR (default: a new temporary folder) holds the nginx and Redis configuration, every log, each
# replica's reference store (`references-I`: its own, as on separate nodes without a shared
# volume; they share references through Redis; a --cache-dir among the serve flags overrides), and
# `cluster.state`, one line per process ("nginx PID PORT", "redis PID SOCKET", "replica I PID
# PORT"), rewritten whenever a process is restarted; tests and scripts read it.
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
replicas=3 port=8889 host=127.0.0.1 workers=0 dir="" serve_flags=()
while (($#)); do
  case $1 in
    --replicas) replicas=$2; shift 2 ;;
    --port) port=$2; shift 2 ;;
    --host) host=$2; shift 2 ;;
    --workers) workers=$2; shift 2 ;;
    --dir) dir=$2; shift 2 ;;
    --) shift; serve_flags=("$@"); break ;;
    -h|--help) sed -n '2,12p' "$0"; exit 0 ;;
    *) echo "cluster: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
bin=${SHADELAB_BIN:-$root/build/shadelab}
[[ -x $bin ]] || { echo "cluster: $bin is not built (tools/build.sh)" >&2; exit 1; }
for tool in nginx redis-server redis-cli; do
  command -v "$tool" >/dev/null || [[ -x /usr/sbin/$tool ]] || { echo "cluster: $tool is missing (tools/setup.sh installs it)" >&2; exit 1; }
done
nginx_bin=$(command -v nginx || echo /usr/sbin/nginx)
[[ -n $dir ]] || dir=$(mktemp -d -t shadelab-cluster.XXXXXX)
mkdir -p "$dir/nginx-temp"
rm -f "$dir/cluster.state" "$dir"/replica-*.log  # an earlier cluster's, in a reused folder
dir=$(cd "$dir" && pwd)
# nginx's workers run as an unprivileged user when it is started as root: they must reach the temp folders.
chmod 755 "$dir" "$dir/nginx-temp"
cores=$(nproc)
((workers > 0)) || workers=$(( cores / replicas > 0 ? cores / replicas : 1 ))
# The replicas share this machine's cores: each worker's llvmpipe gets its share, not all of them.
lp_threads=$(( cores / (replicas * workers) > 0 ? cores / (replicas * workers) : 1 ))

declare -A replica_pid replica_port
redis_pid="" nginx_pid="" stopping=0
socket=$dir/redis.sock

write_state() {
  {
    echo "nginx $nginx_pid $port"
    echo "redis $redis_pid $socket"
    for ((i = 1; i <= replicas; i++)); do echo "replica $i ${replica_pid[$i]:-0} ${replica_port[$i]:-0}"; done
  } >"$dir/cluster.state.tmp"
  mv "$dir/cluster.state.tmp" "$dir/cluster.state"
}

# An HTTP GET over bash's /dev/tcp (no curl on a minimal Debian): true when it answers 200.
http_ok() {
  local status
  { exec 3<>"/dev/tcp/$1/$2"; } 2>/dev/null || return 1  # (a bare `exec 2>...` would silence the script)
  printf 'GET %s HTTP/1.0\r\nHost: %s\r\n\r\n' "$3" "$1" >&3
  read -r -t 5 _ status _ <&3 || status=""
  exec 3<&- 3>&-
  [[ $status == 200 ]]
}

wait_until() {  # SECONDS WHAT COMMAND...
  local deadline=$((SECONDS + $1)) what=$2
  shift 2
  until "$@"; do
    ((SECONDS < deadline)) || { echo "cluster: $what did not come up; see $dir" >&2; return 1; }
    sleep 0.1
  done
}

new_line_says() {  # LOG EARLIER_LINES TEXT
  tail -n +$(($2 + 1)) "$1" | grep -q "$3"
}

start_redis() {
  # Bounded and evicting: the replicas keep what they need themselves, Redis only shares it.
  redis-server --port 0 --unixsocket "$socket" --unixsocketperm 700 --save '' --appendonly no \
    --maxmemory "${SHADELAB_REDIS_MAXMEMORY:-512mb}" --maxmemory-policy allkeys-lru \
    --logfile "$dir/redis.log" --daemonize no &
  redis_pid=$!
  wait_until 10 "redis" redis-cli -s "$socket" ping >/dev/null 2>&1
}

# Starts replica I on its port (0 the first time: the kernel picks one, read back from its log).
start_replica() {
  local i=$1 log="$dir/replica-$1.log"
  local earlier=0  # lines an earlier run of this replica wrote: its port is not this one's
  [[ -f $log ]] && earlier=$(wc -l <"$log")
  local store=(--cache-dir "$dir/references-$i")
  [[ " ${serve_flags[*]} " == *" --cache-dir "* ]] && store=()
  "$bin" serve --host 127.0.0.1 --port "${replica_port[$i]:-0}" --workers "$workers" --lp-threads "$lp_threads" --redis "unix://$socket" \
    --trusted-proxy 127.0.0.1 --max-connections-per-address 0 "${store[@]}" "${serve_flags[@]}" >>"$log" 2>&1 &
  replica_pid[$i]=$!
  # The whole line: " with" follows the port, so a line still being written is not read short.
  wait_until 30 "replica $i" new_line_says "$log" "$earlier" "serving on http://[0-9.]*:[0-9]* with"
  replica_port[$i]=$(tail -n +$((earlier + 1)) "$log" | grep -o 'serving on http://[0-9.]*:[0-9]* with' | tail -1 | sed 's/.*:\([0-9]*\) with/\1/')
  wait_until 60 "replica $i readiness" http_ok 127.0.0.1 "${replica_port[$i]}" /readyz
}

start_nginx() {
  local upstreams="" max_body_mb=16
  for ((i = 1; i <= replicas; i++)); do
    # One failure takes a replica out for 2 s; nginx then tries it again (a restarted one comes back).
    upstreams+="    server 127.0.0.1:${replica_port[$i]} max_fails=1 fail_timeout=2s;"$'\n'
  done
  local k  # the replicas' --max-body-mb, in either form, is nginx's body limit too
  for ((k = 0; k < ${#serve_flags[@]}; k++)); do
    case ${serve_flags[k]} in
      --max-body-mb=*) max_body_mb=${serve_flags[k]#*=} ;;
      --max-body-mb) max_body_mb=${serve_flags[k + 1]:-$max_body_mb} ;;
    esac
  done
  awk -v upstreams="$upstreams" -v run_dir="$dir" -v listen="$host:$port" -v body="$max_body_mb" \
    -v rate="${SHADELAB_NGINX_API_RATE:-20}" -v burst="${SHADELAB_NGINX_API_BURST:-40}" -v conns="${SHADELAB_NGINX_CONNECTIONS_PER_ADDRESS:-32}" '
    { gsub(/@RUN_DIR@/, run_dir); gsub(/@LISTEN@/, listen); gsub(/@MAX_BODY_MB@/, body); gsub(/@API_RATE@/, rate);
      gsub(/@API_BURST@/, burst); gsub(/@CONNECTIONS_PER_ADDRESS@/, conns)
      if ($0 ~ /@UPSTREAM_SERVERS@/) { printf "%s", upstreams; next } print }' \
    "$root/deploy/nginx/shadelab.conf.template" >"$dir/nginx.conf"
  "$nginx_bin" -t -q -p "$dir" -c "$dir/nginx.conf" -e "$dir/nginx-error.log"
  "$nginx_bin" -p "$dir" -c "$dir/nginx.conf" -e "$dir/nginx-error.log" -g 'daemon off;' &
  nginx_pid=$!
  wait_until 10 "nginx" http_ok "$host" "$port" /livez
}

stop_all() {
  ((stopping)) && return
  stopping=1
  trap - INT TERM
  [[ -n $nginx_pid ]] && kill -QUIT "$nginx_pid" 2>/dev/null || true  # finish the requests in flight
  for pid in "${replica_pid[@]}"; do kill -TERM "$pid" 2>/dev/null || true; done
  [[ -n $redis_pid ]] && kill -TERM "$redis_pid" 2>/dev/null || true
  wait 2>/dev/null || true
  echo "cluster: stopped" >&2
}
trap 'stop_all; exit 0' INT TERM
trap 'stop_all' EXIT

start_redis
for ((i = 1; i <= replicas; i++)); do start_replica "$i"; done
start_nginx
write_state
echo "cluster: listening on http://$host:$port (nginx) -> $replicas replicas, $workers render workers each, sharing through Redis at unix://$socket; logs and state in $dir" >&2

# Supervise: a replica or Redis that exits is started again; nginx exiting ends the cluster.
while ((!stopping)); do
  wait -n || true
  ((stopping)) && break
  if ! kill -0 "$nginx_pid" 2>/dev/null; then echo "cluster: nginx exited; stopping" >&2; exit 1; fi
  if ! kill -0 "$redis_pid" 2>/dev/null; then
    echo "cluster: redis exited; starting it again (the replicas recompute meanwhile)" >&2
    start_redis
  fi
  for ((i = 1; i <= replicas; i++)); do
    if ! kill -0 "${replica_pid[$i]}" 2>/dev/null; then
      echo "cluster: replica $i exited; starting it again on port ${replica_port[$i]}" >&2
      start_replica "$i" || echo "cluster: replica $i did not come back; nginx routes around it" >&2
    fi
  done
  write_state
done
