#!/usr/bin/env bash
# The GPU checks that wait for a lent GPU machine (docs/benchmarks.md, "Measuring on a lent
# GPU"), run there from the repository root with .device carried (bench/device/bundle.sh):
#   the GL agreement tests; Table 2 with the depth lookup (issue 23); the depth of the central
#   view and of every view on the GPU (issue 22). What they print and write lands in $OUT.
set -uo pipefail
exec > >(tee "$OUT/log.txt") 2>&1
exec 3>&1  # the log, for what `timed` says whatever a command's own output is redirected to
for deb in .device/gl/*.deb; do dpkg -x "$deb" /; done
ldconfig
vendor=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
[ -f $vendor ] && export __EGL_VENDOR_LIBRARY_FILENAMES=$vendor
mkdir -p /tmp/lfcam && tar -xJf .device/bundle.tar.xz -C /tmp/lfcam
export LD_LIBRARY_PATH=/tmp/lfcam/lib
lfcam=/tmp/lfcam/bin/lfcam
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
echo "cores: $(nproc)"
work=/tmp/work
mkdir -p $work
timed() {
  local start rc
  start=$(date +%s%N)
  "$@"
  rc=$?
  echo "== exit $rc after $((($(date +%s%N) - start) / 1000000)) ms: $*" >&3
}
echo "### the GL agreement tests"
timed timeout 180 /tmp/lfcam/bin/lfcam_tests \
  --gtest_filter='GlRenderer.*:ViewWindows.*:GlCostVolume.*' >"$OUT/tests.txt" 2>&1
grep -E "^\[  (PASSED|FAILED) |tests ran" "$OUT/tests.txt"
echo "### Table 2 with the depth lookup"
timed $lfcam simulate lightfield --out $work/p.lf --st-domain=-1.2,-1.2,1.2,1.2 --supersampling 1 \
  --depth-out $work/p_depth --quiet
timed timeout 240 $lfcam bench table2 --backend gl --lightfield $work/p.lf --interpolation depth \
  --depth $work/p_depth --json "$OUT/t2_depth.json" --quiet
echo "### depth on the GPU"
timed $lfcam simulate lightfield --out $work/s.lf --st-res 416x384 --quiet
timed timeout 60 $lfcam depth $work/s.lf --all --out $work/s_all --backend gl --json >"$OUT/depth_all_416.json"
timed $lfcam simulate lightfield --out $work/u.lf --quiet
timed timeout 60 $lfcam depth $work/u.lf --out $work/d.png --backend gl --json >"$OUT/depth_central.json"
timed timeout 200 $lfcam depth $work/u.lf --all --out $work/all --backend gl --json >"$OUT/depth_all.json"
