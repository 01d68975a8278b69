#!/usr/bin/env bash
# The sanitizer job's CLI runs (docs/ci.md): every subcommand on bad input --
# missing, empty, truncated, bit-flipped and non-regular files, a grid whose
# size fields overflow, mutated scene JSON, garbage option values, unusable
# output paths -- run with the ASan+UBSan binary. Each run must end without a
# sanitizer report, without a signal and within a timeout; the exit status is
# printed (2 is the refusal every bad input should get) but judged by the CLI
# tests and scripts/probe.py, not here: this script asks the sanitizers.
#
#   tests/sanitize/cli_bad_input.sh PENUMBRA_BINARY
#
# Needs ASAN_OPTIONS/UBSAN_OPTIONS/LSAN_OPTIONS from .ci/run (or set by hand:
# docs/ci.md). Exits 1 if any run had a finding.
set -euo pipefail
cli=$(realpath "${1:?usage: cli_bad_input.sh PENUMBRA_BINARY}")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"

# Fixtures: valid files first, then damaged copies of them.
"$cli" example --out ok >/dev/null
"$cli" render-scene contact --shadow-map ok/sm.exr --receivers ok/rx.exr --truth ok/gt.exr \
  --map-size 64 --view-size 16x12 --samples 4 >/dev/null
"$cli" sdf-bake --scene fence --out ok/fence.pnsdf --voxel 0.5 >/dev/null
"$cli" dsm-build --scene layers --out ok/dsm.exr --size 16 --samples 4 >/dev/null
mkdir -p ok/pismo
"$cli" pismo-build --scene contact --out ok/pismo --light-level 0 --map-size 16 --receivers ok/rx.exr >/dev/null
mkdir -p bad
: >bad/empty.exr
head -c 1000 ok/shadow_map.exr >bad/truncated.exr
head -c 4096 /dev/urandom >bad/random.exr
cp ok/shadow_map.exr bad/flipped.exr
printf '\xff\xff\xff\xff' | dd of=bad/flipped.exr bs=1 seek=400 conv=notrunc status=none
mkfifo bad/fifo.exr
# 36-byte grid whose nx*ny*nz wraps to 0 in 64 bits (issue 11, defect 2).
printf 'PNSDFGR1\x00\x00\x40\x00\x00\x00\x20\x00\x00\x00\x20\x00' >bad/wrap.pnsdf
printf '\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x80\x3f' >>bad/wrap.pnsdf
head -c 30 ok/fence.pnsdf >bad/short.pnsdf
echo '{"primitives": [' >bad/truncated.json
echo '{"map_size": 1e999}' >bad/overflow.json
echo '[]' >bad/array.json
printf 'x%.0s' {1..300} >bad/long-name
# Pismo's maps with a bit-flipped map file (its ids channel among the bytes),
# and a manifest whose surface count does not cover the maps' ids.
cp -r ok/pismo bad/pismo-flipped
printf '\xff\xff\xff\xff' | dd of=bad/pismo-flipped/map-0001.exr bs=1 seek=600 conv=notrunc status=none
cp -r ok/pismo bad/pismo-count
sed -i 's/"surfaces": [0-9]*/"surfaces": 1/' bad/pismo-count/pismo.json

sm=ok/shadow_map.exr rx=ok/receivers.exr
runs=(
  ""
  "bogus-command"
  "shade"
  "shade --method vsm --shadow-map missing.exr --receivers $rx --out o.exr"
  "shade --method vsm --shadow-map bad/empty.exr --receivers $rx --out o.exr"
  "shade --method vsm --shadow-map bad/truncated.exr --receivers $rx --out o.exr"
  "shade --method vssm --shadow-map bad/random.exr --receivers $rx --out o.exr"
  "shade --method msm --shadow-map bad/flipped.exr --receivers $rx --out o.exr"
  "shade --method vsm --shadow-map ok --receivers $rx --out o.exr"
  "shade --method vsm --shadow-map $rx --receivers $sm --out o.exr"
  "shade --method vsm --shadow-map $sm --receivers $rx --out o.exr --radius -1"
  "shade --method vsm --shadow-map $sm --receivers $rx --out o.exr --radius nan"
  "shade --method vssm --shadow-map $sm --receivers $rx --out o.exr --light-size 1e40"
  "shade --method evsm4 --shadow-map $sm --receivers $rx --out o.exr --exponents 99,x"
  "shade --method msm --shadow-map $sm --receivers $rx --out /nonexistent/o.exr"
  "shade --method bogus --shadow-map $sm --receivers $rx --out o.exr"
  "shade --method dsm --deep-map $sm --receivers $rx --out o.exr"
  "shade --method dsm --deep-map bad/truncated.exr --receivers $rx --out o.exr"
  "shade --method dsm --deep-map bad/flipped.exr --receivers $rx --out o.exr"
  "shade --method dsm --deep-map ok/dsm.exr --receivers bad/flipped.exr --out o.exr --filter tent --radius 2"
  "shade --method dsm --shadow-map $sm --receivers $rx --out o.exr"
  "shade --method pismo --pismo-maps ok/pismo --receivers ok/rx.exr --out o.exr --rays 4"
  "shade --method pismo --pismo-maps bad/pismo-flipped --receivers ok/rx.exr --out o.exr --rays 4"
  "shade --method pismo --pismo-maps bad/pismo-count --receivers ok/rx.exr --out o.exr --rays 4"
  "shade --method pismo --scene contact --map-size 16 --receivers bad/flipped.exr --out o.exr --rays 4"
  "blur --in $sm --guide bad/truncated.exr --out o.exr"
  "blur --in $sm --guide $rx --out o.exr --radius 100000"
  "sdf-shade --grid bad/wrap.pnsdf --receivers ok/rx.exr --out o.exr --k 2 --light-direction 0,1,0"
  "sdf-shade --grid bad/short.pnsdf --receivers ok/rx.exr --out o.exr --k 2 --light-direction 0,1,0"
  "sdf-shade --grid ok/fence.pnsdf --receivers bad/flipped.exr --out o.exr --k 2 --light-direction 0,1,0"
  "sdf-shade --scene bad/truncated.json --receivers ok/rx.exr --out o.exr"
  "sdf-bake --scene fence --out o.pnsdf --voxel 0"
  "sdf-bake --scene fence --out o.pnsdf --voxel -nan"
  "sdf-bake --scene bad/overflow.json --out o.pnsdf"
  "render-scene bad/array.json --shadow-map a.exr --receivers b.exr --truth c.exr"
  "render-scene bad/overflow.json --shadow-map a.exr --receivers b.exr --truth c.exr"
  "render-scene contact --shadow-map a.exr --receivers b.exr --truth c.exr --map-size 0"
  "render-scene contact --shadow-map a.exr --receivers b.exr --truth c.exr --view-size 0x-3"
  "render-scene bad/long-name --shadow-map a.exr --receivers b.exr --truth c.exr"
  "example --out bad/empty.exr"
  "demo --quick --method bogus --out d"
  "info --bogus"
)
# A FIFO as input must be refused, not waited on (defect 5): run it with the
# timeout like every other case.
runs+=("shade --method vsm --shadow-map bad/fifo.exr --receivers $rx --out o.exr")

findings=0
for args in "${runs[@]}"; do
  rc=0
  # shellcheck disable=SC2086  # each case is a word list on purpose
  timeout -k 5 30 "$cli" $args >out.txt 2>err.txt </dev/null || rc=$?
  verdict=ok
  if grep -qE 'ERROR: (AddressSanitizer|LeakSanitizer)|runtime error:|SUMMARY: UndefinedBehaviorSanitizer' err.txt; then
    verdict=SANITIZER
  elif ((rc == 124 || rc == 137)); then
    verdict=TIMEOUT
  elif ((rc > 128)); then
    verdict=SIGNAL
  fi
  printf '%-9s exit %3d  penumbra %s\n' "$verdict" "$rc" "$args"
  if [[ $verdict != ok ]]; then
    findings=$((findings + 1))
    sed 's/^/    /' err.txt | head -n 30
  fi
done
echo "cli_bad_input: ${#runs[@]} runs, $findings with a finding"
((findings == 0))
