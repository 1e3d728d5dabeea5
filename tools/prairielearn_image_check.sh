#!/usr/bin/env bash
# The PrairieLearn grader image's stage (Dockerfile, prairielearn-grader) built by hand in a
# throwaway minimal Debian 12 root, for machines without a Docker daemon, and its entrypoint run
# the way PrairieLearn runs it: a job in /grade with a student's hand-in, no network, results read
# back. It proves the stage installs everything the binary loads (tools/setup.sh runtime) and
# nothing of the build.
#
#   sudo tools/prairielearn_image_check.sh [BUILT_SHADELAB]     # default: build/shadelab
#
# Needs root, debootstrap (installed when missing) and apt's network access for the root's set-up.
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
bin=$(readlink -f "${1:-$repo/build/shadelab}")
root=$(mktemp -d /tmp/shadelab-pl-grader.XXXXXX)
[[ $(id -u) -eq 0 ]] || { echo "prairielearn_image_check: run as root (debootstrap and chroot need it)" >&2; exit 1; }
[[ -x $bin ]] || { echo "prairielearn_image_check: no built shadelab at $bin" >&2; exit 1; }
command -v debootstrap >/dev/null || { apt-get update -qq && apt-get install -y -qq debootstrap; }
mounts=()
cleanup() {
  for ((i = ${#mounts[@]} - 1; i >= 0; i--)); do umount -l "${mounts[i]}" 2>/dev/null || true; done
  [[ ${KEEP_ROOT:-0} == 1 ]] || rm -rf --one-file-system "$root"
}
trap cleanup EXIT

echo "prairielearn_image_check: debootstrap --variant=minbase bookworm $root"
debootstrap --variant=minbase bookworm "$root" >"$root.debootstrap.log" 2>&1 || { tail -20 "$root.debootstrap.log" >&2; exit 1; }
for m in proc sys dev; do
  mount --bind "/$m" "$root/$m"
  mounts+=("$root/$m")
done
cp /etc/resolv.conf "$root/etc/resolv.conf"
if compgen -G "/usr/local/share/ca-certificates/*.crt" >/dev/null; then
  mkdir -p "$root/usr/local/share/ca-certificates" && cp /usr/local/share/ca-certificates/*.crt "$root/usr/local/share/ca-certificates/"
fi
in_root() { chroot "$root" /usr/bin/env -i HOME=/root PATH=/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin LANG=C.UTF-8 "$@"; }

# The stage's steps, as the Dockerfile writes them.
cp "$repo/tools/setup.sh" "$root/tmp/setup.sh"
in_root bash -c '/tmp/setup.sh runtime && rm -rf /var/lib/apt/lists/* /tmp/setup.sh'
install -m 755 "$bin" "$root/usr/local/bin/shadelab"
install -m 755 "$repo/prairielearn/entrypoint" "$root/usr/local/bin/shadelab-prairielearn"
in_root env SHADELAB_SOFTWARE=1 shadelab course warm --cache-dir /var/lib/shadelab/reference-store >/dev/null

# A job as PrairieLearn lays it out: the hand-in's files flat, as its upload keeps them, the
# specular code left at the diffuse reference (one failing test, with its heat map).
job=$root/grade
mkdir -p "$job/student" "$job/data"
angles=0,19.88,39.79,59.95,79.7,99.83,119.74,139.91,159.77
for p in normals diffuse specular; do "$bin" render --preset "$p" --prefix "$p" --frames-dir "$job/student" --angles "$angles" >/dev/null; done
cp "$repo/shaders/normals_vert.js" "$job/student/starter_vert.js"
cp "$repo/shaders/normals_frag.js" "$job/student/starter_frag.js"
cp "$repo/shaders/specular_vert.js" "$job/student/phong_vert.js"
cp "$repo/shaders/diffuse_frag.js" "$job/student/phong_frag.js"
echo '{"params": {"shadelab": {}}, "submitted_answers": {}}' >"$job/data/data.json"

# PrairieLearn's run: no network (a new network namespace), the entrypoint, the results.
start=$(date +%s.%N)
unshare --net chroot "$root" /usr/bin/env -i PATH=/usr/local/bin:/usr/bin:/bin SHADELAB_SOFTWARE=1 SHADELAB_TIME_LIMIT_S=45 \
  /usr/local/bin/shadelab-prairielearn
end=$(date +%s.%N)
python3 - "$job/results/results.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
assert r.get("gradable", True), r
print(f"score {r['score']}: {r['message']}")
failed = [t["name"] for t in r["tests"] if t["points"] < t["max_points"]]
assert failed and all("Specular" in n for n in failed), failed
assert any("images" in t for t in r["tests"]), "the failed code test's heat map"
PY
echo "prairielearn_image_check: graded in the grader's root in $(echo "$end - $start" | bc) s (warm references, no network)"
