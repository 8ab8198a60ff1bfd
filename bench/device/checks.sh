#!/usr/bin/env bash
# The checks and figures that need a lent GPU machine (docs/benchmarks.md, "Measuring on a lent
# GPU"), run there from the repository root with .device carried (bench/device/bundle.sh):
#   the GL agreement tests; every GL row of issue 23 (Tables 1 and 2 for each integrator and
#   lookup, the user's light field beside the bench's, the viewer's frames, a moving eye) and
#   the depth of the central view and of every view on the GPU (issue 22). What they print and
#   write lands in $OUT (log.txt, tests.txt, one JSON file a table). About five minutes on an
#   H100 or H200; the most needed first, so that a run stopped at its limit still says them.
# LFCAM_CHECKS_SMALL=1 runs the same commands on small light fields (a check of the script
# itself, on any machine with lfcam's bundle unpacked; its figures mean nothing).
set -uo pipefail
exec > >(tee "$OUT/log.txt") 2>&1
exec 3>&1  # the log, for what `timed` says whatever a command's own output is redirected to
if command -v nvidia-smi >/dev/null; then
  for deb in .device/gl/*.deb; do dpkg -x "$deb" /; done
  ldconfig
  vendor=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
  [ -f $vendor ] && export __EGL_VENDOR_LIBRARY_FILENAMES=$vendor
  nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
fi
bundle=${LFCAM_BUNDLE:-/tmp/lfcam}
mkdir -p "$bundle" && tar -xJf .device/bundle.tar.xz -C "$bundle"
export LD_LIBRARY_PATH=$bundle/lib
lfcam=$bundle/bin/lfcam
echo "cores: $(nproc); $(git log -1 --format='%h %s' 2>/dev/null || echo 'no git')"
work=${LFCAM_WORK:-/tmp/work}
mkdir -p "$work"
full=() small=(--st-res 416x384) table_limit=150
if [ "${LFCAM_CHECKS_SMALL:-0}" = 1 ]; then
  small=(--st-res 96x88)
  full=(--st-res 128x120)
  table_limit=15  # llvmpipe: each table is only started, its flags checked
fi
timed() {
  local start rc
  start=$(date +%s%N)
  "$@"
  rc=$?
  echo "== exit $rc after $((($(date +%s%N) - start) / 1000000)) ms: $*" >&3
}
table() {  # table NAME ARGS...: lfcam bench ARGS --backend gl, its JSON as $OUT/NAME.json
  local name=$1
  shift
  timed timeout $table_limit $lfcam bench "$@" --backend gl --min-seconds 0.5 --json "$OUT/$name.json" --quiet
}
echo "### the GL agreement tests"
timed timeout 240 "$bundle/bin/lfcam_tests" \
  --gtest_filter='GlRenderer.*:ViewWindows.*:GlCostVolume.*:ReachAndView/GlCostVolumeAgreement.*' \
  >"$OUT/tests.txt" 2>&1
grep -E "^\[  (PASSED|FAILED) |tests ran|^\[  FAILED" "$OUT/tests.txt"
echo "### the light fields: the bench's over [-1.2, 1.2]^2 with its depth, the user's over [0, 1]^2"
timed $lfcam simulate lightfield --out $work/p.lf --st-domain=-1.2,-1.2,1.2,1.2 --supersampling 1 \
  --depth-out $work/p_depth "${full[@]}" --quiet
timed $lfcam simulate lightfield --out $work/u.lf --supersampling 1 "${full[@]}" --quiet
echo "### Tables 1 and 2 (issue 23)"
table t1 table1 --lightfield $work/p.lf
table t2_lens table2 --lightfield $work/p.lf
table t2_cameras_user table2 --lightfield $work/p.lf --integrator cameras --users-case
table t2_quadlimit_user table2 --lightfield $work/p.lf --integrator cameras-quadrilinear --users-case
echo "### the viewer's frames and a moving eye (issue 23)"
timed timeout 60 $lfcam bench viewer --backend gl --lightfield $work/u.lf --min-runs 60 --quiet
timed timeout 60 $lfcam bench viewer --backend gl --lightfield $work/u.lf --integrator cameras \
  --min-runs 60 --quiet
for integrator in cameras cameras-quadrilinear; do
  timed timeout 60 $lfcam render $work/u.lf --backend gl --integrator $integrator --aperture 256 \
    --eye 300,275,4100 --size 1024 --repeat 20 --out $work/e.png
done
timed timeout 60 $lfcam render $work/p.lf --backend gl --interpolation depth --depth $work/p_depth \
  --size 1024 --repeat 20 --out $work/between.png
echo "### depth on the GPU (issue 22)"
timed timeout 60 $lfcam depth $work/u.lf --out $work/d.png --backend gl --json >"$OUT/depth_central.json"
timed $lfcam simulate lightfield --out $work/s.lf "${small[@]}" --quiet
timed timeout 60 $lfcam depth $work/s.lf --all --out $work/s_all --backend gl --json >"$OUT/depth_all_416.json"
echo "### Table 2 with the depth lookup (issue 23; the longest, last but one)"
table t2_depth table2 --lightfield $work/p.lf --interpolation depth --depth $work/p_depth
echo "### every view's depth, full size (issue 22; the longest, last)"
timed timeout 200 $lfcam depth $work/u.lf --all --out $work/all --backend gl --json >"$OUT/depth_all.json"
echo "### done"
