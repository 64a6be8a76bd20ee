#!/usr/bin/env bash
# A full disk (docs/architecture.md#output-files): magFoam and magForces on a
# 200 kB tmpfs must stop with exit != 0 naming the file they could not write,
# leave every file either whole or absent (no cut bodies.yaml, .pvd or .vtp;
# CSV rows whole but maybe the last), and a restart once there is room again
# must resume from the newest complete time and end bit for bit where a run
# on a roomy disk ends.
#
# Mounting needs a mount namespace: root, or an unprivileged user namespace.
# Where neither is allowed the test is skipped (exit 77).
# Usage: run.sh MAGFOAM MAGFORCES SRC TWOCUBES WORK
set -u
magFoam=$1 magForces=$2 src=$3 twoCubes=$4 work=$5

if [[ "${MAG_IN_NAMESPACE:-}" != 1 ]]; then
  for ns in "unshare --mount" "unshare --user --map-root-user --mount"; do
    if $ns true 2>/dev/null; then
      MAG_IN_NAMESPACE=1 exec $ns "$0" "$@"
    fi
  done
  echo "SKIP: no mount namespace here (not root, no user namespaces)"
  exit 77
fi

fail() { echo "FAIL: $*"; exit 1; }

rm -rf "$work"
mkdir -p "$work/disk" "$work/roomy"
mount -t tmpfs -o size=200k tmpfs "$work/disk" 2>/dev/null || { echo "SKIP: cannot mount a tmpfs"; exit 77; }
mount --make-private "$work/disk" 2>/dev/null || true

# 1. The reference run, on a roomy disk.
cp -r "$src" "$work/roomy/case"
"$magFoam" -case "$work/roomy/case" >"$work/roomy.log" 2>&1 || { cat "$work/roomy.log"; fail "the reference run failed"; }

# 2. The same run on 200 kB.
cp -r "$src" "$work/disk/case"
"$magFoam" -case "$work/disk/case" >"$work/full.log" 2>&1
rc=$?
cat "$work/full.log" | tail -5
[[ $rc -ne 0 ]] || fail "magFoam exited 0 on a full disk"
grep -q "magFoam: stopped: $work/disk/case/.*No space left on device" "$work/full.log" ||
  fail "the message does not name the file and the reason"

# Every file is whole: bodies.yaml of every time folder reads as a state
# (ends with the last body's magnetization line), the series is closed XML,
# each .vtp is closed, and the CSVs hold whole rows but maybe a cut last one.
case=$work/disk/case
for f in "$case"/[0-9]*/bodies.yaml; do
  [[ -e "$f" ]] || continue
  tail -1 "$f" | grep -q "magnetization: \[.*\]   # A/m, body frame" || fail "$f is cut"
done
for f in "$case"/VTK/*.vtp "$case"/VTK/bodies.pvd; do
  [[ -e "$f" ]] || continue
  tail -1 "$f" | grep -q "</VTKFile>" || fail "$f is cut"
done
ls "$case"/*/*.tmp "$case"/VTK/*.tmp 2>/dev/null && fail "temporary files were left behind"
newest=$(ls -d "$case"/[0-9]* | xargs -n1 basename | sort -g | tail -1)
echo "newest complete time on the full disk: $newest"

# 3. Room again: the restart resumes from the newest complete time and ends
#    where the reference run ends.
mount -o remount,size=20m "$work/disk" || fail "cannot grow the tmpfs"
echo "startFrom: latestTime" >>"$case/system/controlDict.yaml"
"$magFoam" -case "$case" >"$work/restart.log" 2>&1 || { cat "$work/restart.log"; fail "the restart failed"; }
grep -q "Restarting from $case/$newest " "$work/restart.log" || { cat "$work/restart.log"; fail "did not restart from $newest"; }
cmp "$work/roomy/case/0.02/bodies.yaml" "$case/0.02/bodies.yaml" || fail "the restarted run ends elsewhere"
cmp "$work/roomy/case/postProcessing/bodies.csv" "$case/postProcessing/bodies.csv" ||
  fail "bodies.csv differs from the reference run's"
cmp "$work/roomy/case/postProcessing/energy.csv" "$case/postProcessing/energy.csv" ||
  fail "energy.csv differs from the reference run's"

# 4. magForces: a sweep of 603 rows (about 90 kB) on 48 kB, of which the five
#    dictionaries take a page (4 kB) each.
mkdir -p "$work/small"
mount -t tmpfs -o size=48k tmpfs "$work/small" || fail "cannot mount the small tmpfs"
mkdir -p "$work/small/case/system" "$work/small/case/constant"
cp "$twoCubes"/system/{controlDict,forcesDict,magSchemes}.yaml "$work/small/case/system/"
cp "$twoCubes"/constant/{bodies,materials}.yaml "$work/small/case/constant/"
"$magForces" -case "$work/small/case" >"$work/forces.log" 2>&1
rc=$?
tail -3 "$work/forces.log"
[[ $rc -ne 0 ]] || fail "magForces exited 0 on a full disk"
grep -q "magForces: stopped: $work/small/case/postProcessing/forces.csv: cannot write (No space left on device)" \
  "$work/forces.log" || fail "magForces does not name forces.csv and the reason"
echo "PASS"
