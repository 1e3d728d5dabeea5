#!/usr/bin/env bash
# Packs ShadeLab and its GPU check (run.sh) with every library they load, for a Linux x86-64
# machine with glibc >= 2.36 and a GPU driver but nothing else installed (no package manager, no
# network). OpenImageIO's Debian dependency chain is cut by replacing the leaf libraries ShadeLab
# never calls with generated stubs of the same sonames and symbols (gen_stubs.py; a call to one
# returns 0, STUB_TRACE=1 prints each). glvnd's libEGL/libGLESv2 travel too (run.sh uses them only
# where the machine has none); the GPU driver's EGL vendor file is the machine's.
#
#   tools/gpu_check/pack.sh BUILD_DIR OUT.tar.xz        (needs gcc, readelf, python3, xz; ~2 min)
#   on the target: tar -xJf OUT.tar.xz && sl/run.sh [OUT_DIR]
#
# Adapted from the workplace's gpu-bundle tool (pack.sh, gen_stubs.py, closure.py, egl_probe.c);
# this copy also packs the tests and benchmarks the check runs and the data they read.
set -euo pipefail
BUILD=$(cd "$1" && pwd); OUTF=$(realpath -m "$2")
HERE=$(cd "$(dirname "$0")" && pwd); REPO=$(cd "$HERE/../.." && pwd); WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
export BUNDLE_LIBS=$WORK/libs; mkdir -p "$BUNDLE_LIBS" "$WORK/sl/lib" "$WORK/sl/bin" "$WORK/sl/glvnd"
gcc -O2 -o "$WORK/egl_probe" "$HERE/egl_probe.c" -lEGL -lGLESv2
ROOTS=$BUILD/shadelab,$WORK/egl_probe
for b in bench/load_bench bench/soak_bench tests/golden_test tests/webgl_rules_test; do
  [ -x "$BUILD/$b" ] || { echo "pack.sh: $BUILD/$b is not built (ninja -C $BUILD)" >&2; exit 1; }
  ROOTS="$ROOTS,$BUILD/$b"
done
for r in ${ROOTS//,/ }; do
  ldd "$r" | awk '$2 == "=>" && $3 ~ /^\// {print $1, $3}' | while read -r n f; do
    case $n in
      libEGL.so*|libGLESv2.so*|libGLdispatch.so*) cp -Ln "$f" "$WORK/sl/glvnd/$n" 2>/dev/null || true; continue;;
      libc.so*|libm.so*|libGLX*|libGL.so*|libdl.so*|libpthread*|librt.so*) continue;;
    esac
    [ -f "$BUNDLE_LIBS/$n" ] || cp -L "$f" "$BUNDLE_LIBS/$n"
  done
done
STUBS="libopencv_core.so.406,libopencv_imgproc.so.406,libopencv_videoio.so.406,libdcmimage.so.17,libdcmimgle.so.17,libdcmdata.so.17,liboflog.so.17,libofstd.so.17,libavcodec.so.59,libavformat.so.59,libavutil.so.57,libswscale.so.6,libgif.so.7,libheif.so.1,libopenjp2.so.7,libopenvdb.so.10.0,libraw_r.so.20,libtiff.so.6,libwebp.so.7,libwebpdemux.so.2"
# version queries OpenImageIO turns into strings when it lists its plugins must return "" rather than NULL
export STUB_RET_STR="TIFFGetVersion,opj_version,heif_get_version,libraw_version,av_version_info,avcodec_configuration,avformat_configuration,avutil_configuration,avcodec_license,avformat_license,avutil_license,swscale_configuration,swscale_license"
cd "$WORK"; cp "$HERE/gen_stubs.py" "$HERE/closure.py" .
python3 gen_stubs.py "$STUBS" "$WORK/stubs" "$ROOTS"
python3 -c "
import sys; sys.path.insert(0,'.')
from closure import closure
stubs=set('$STUBS'.split(','))
print('\n'.join(sorted(n for n in closure('$ROOTS'.split(','),stubs) if n not in stubs)))" > kept.txt
while read -r n; do cp "$BUNDLE_LIBS/$n" sl/lib/; done < kept.txt
cp stubs/*.so* sl/lib/
for r in ${ROOTS//,/ }; do strip -o "sl/bin/$(basename "$r")" "$r"; done
for b in sl/bin/*; do
  LD_LIBRARY_PATH=$WORK/sl/lib ldd "$b" | grep -v -E "$WORK/sl/lib|linux-vdso|libc.so|libm.so|ld-linux|libEGL|libGLES|libGLdispatch" &&
    { echo "pack.sh: unexpected resolution in $b" >&2; exit 1; } || true
done
# What the tests and the service read: the approved images, the browser's verdicts, the page.
mkdir -p sl/data/tests/webgl_rules
cp -r "$REPO/tests/golden" sl/data/tests/
cp "$REPO/tests/webgl_rules/cases.json" sl/data/tests/webgl_rules/
cp -r "$REPO/web" sl/data/web
cp "$HERE/run.sh" sl/run.sh
LD_LIBRARY_PATH=$WORK/sl/lib sl/bin/shadelab render --preset specular --mesh bunny --grid "$WORK/check.png" >/dev/null
tar -C "$WORK" -cf - sl | xz -6 -T0 > "$OUTF"
ls -la "$OUTF"
