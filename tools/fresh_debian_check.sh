#!/usr/bin/env bash
# Runs the README's test command (tools/test.sh) in a throwaway minimal Debian 12 root, the way a
# new user's machine starts: `debootstrap --variant=minbase bookworm`, nothing else installed.
# A green run on a developer's machine can hide a missing install step (a newer Node, a library
# some other project installed); this cannot. Then PrairieLearn's grader image's stage is built and
# run from the binary it built (tools/prairielearn_image_check.sh).
#
#   sudo tools/fresh_debian_check.sh [ROOT_DIR]     # default: a new folder under /tmp
#
# The committed HEAD is cloned into the root (uncommitted changes are not part of the check). The
# root's apt sources are the ones debootstrap writes (Debian's default mirror); the root and the
# mounts are removed afterwards unless KEEP_ROOT=1. Needs root, debootstrap (installed when
# missing) and the network access apt-get already has.
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
root=${1:-$(mktemp -d /tmp/shadelab-bookworm.XXXXXX)}
[[ $(id -u) -eq 0 ]] || { echo "fresh_debian_check: run as root (debootstrap and chroot need it)" >&2; exit 1; }
command -v debootstrap >/dev/null || { apt-get update -qq && apt-get install -y -qq debootstrap; }

mounts=()
cleanup() {
  for ((i = ${#mounts[@]} - 1; i >= 0; i--)); do umount -l "${mounts[i]}" 2>/dev/null || true; done
  if [[ ${KEEP_ROOT:-0} != 1 ]]; then rm -rf --one-file-system "$root"; fi
}
trap cleanup EXIT

start=$(date +%s)
if [[ ! -x $root/bin/bash ]]; then
  echo "fresh_debian_check: debootstrap --variant=minbase bookworm $root"
  debootstrap --variant=minbase bookworm "$root" >"$root.debootstrap.log" 2>&1 ||
    { tail -20 "$root.debootstrap.log" >&2; exit 1; }
fi
bootstrapped=$(date +%s)
# What the test command needs from the host: processes, devices (EGL's /dev/dri where there is a
# GPU, chromium's /dev/shm), and name resolution for apt.
for m in proc sys dev dev/pts; do
  mkdir -p "$root/$m"
  mount --bind "/$m" "$root/$m"
  mounts+=("$root/$m")
done
cp /etc/resolv.conf "$root/etc/resolv.conf"
# Where this machine reaches the registries through a TLS-inspecting proxy, the root must trust
# the same local certificate authorities (a user's own machine has none, and loses nothing).
extra_env=()
if compgen -G "/usr/local/share/ca-certificates/*.crt" >/dev/null; then
  mkdir -p "$root/usr/local/share/ca-certificates"
  cp /usr/local/share/ca-certificates/*.crt "$root/usr/local/share/ca-certificates/"
  extra_env=(NODE_EXTRA_CA_CERTS=/etc/ssl/certs/ca-certificates.crt)
fi
rm -rf "$root/root/shadelab"
git clone -q "$repo" "$root/root/shadelab"

echo "fresh_debian_check: running tools/test.sh in the root (log: $root/test.log)"
status=0
chroot "$root" /usr/bin/env -i HOME=/root PATH=/usr/sbin:/usr/bin:/sbin:/bin LANG=C.UTF-8 CI=true "${extra_env[@]}" \
  bash -c 'cd /root/shadelab && tools/test.sh' >"$root.test.log" 2>&1 || status=$?
end=$(date +%s)
tail -25 "$root.test.log"
echo "fresh_debian_check: debootstrap $((bootstrapped - start)) s, set-up + build + tests $((end - bootstrapped)) s," \
     "exit status $status (full log: $root.test.log)"
# PrairieLearn's grader image, from the binary this root built: its stage in a root of its own
# with only the runtime packages, the entrypoint run on a job without network.
if ((status == 0)); then
  "$repo/tools/prairielearn_image_check.sh" "$root/root/shadelab/build/shadelab" || status=$?
fi
exit "$status"
