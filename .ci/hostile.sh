#!/usr/bin/env bash
# Hostile and careless inputs to the sylva command, each under a memory cap (ulimit -v):
# every case must end in its expected exit status with a one-line error naming the cause,
# within its time, without a signal (an out-of-memory abort, a hang killed by timeout).
# Prints a table row per case: exit status, peak memory, seconds, first line of the message.
# usage: bash .ci/hostile.sh SYLVA_BINARY SCRATCH_DIR
set -uo pipefail
sylva=$(realpath "$1")
dir=$2
rm -rf "$dir" && mkdir -p "$dir"
cd "$dir" || exit 1
cap_kb=$((3 * 1024 * 1024)) # 3 GiB of address space per case
failures=0

# case NAME EXPECTED_STATUS EXPECTED_WORDS SECONDS -- COMMAND...
case_() {
  local name=$1 want=$2 words=$3 seconds=$4
  shift 5
  local started=$SECONDS
  (ulimit -v "$cap_kb"; exec /usr/bin/time -f '%M' -o time.txt timeout "$seconds" "$@") > out.txt 2> err.txt
  local got=$?
  local peak_mb=$(( $(tail -1 time.txt 2>/dev/null || echo 0) / 1024 ))
  local line
  line=$(grep -v '^Command\|^[[:space:]]*$' err.txt | head -1)
  printf '| %s | %s | %s MB | %s s | %s |\n' "$name" "$got" "$peak_mb" "$((SECONDS - started))" "${line:0:140}"
  if [ "$got" != "$want" ] || ! grep -q -- "$words" err.txt; then
    echo "  FAILED: $name: expected status $want and '$words'" >&2
    failures=$((failures + 1))
  fi
}

printf 'axiom: F\nF -> FF\n' > bomb.lsys
printf 'grammar: kenwood-leafy\nname: %s\n' "$(head -c 300000 /dev/zero | tr '\0' 'x')" > long.species
mkfifo pipe
ln -s forest_target.glb link.glb
: > forest_target.glb

echo '| case | status | peak | time | message |'
echo '|---|---|---|---|---|'
case_ "a doubling grammar at 22 generations (4 M stems)" 1 "pieces" 60 -- "$sylva" tree bomb.lsys --generations 22 --out bomb.obj
case_ "the same at 40 generations" 1 "modules" 60 -- "$sylva" tree bomb.lsys --generations 40 --out bomb.obj
case_ "20 km of 20 m tiles (a million tiles)" 1 "use tiles of at least 79 m" 60 -- "$sylva" tiles --area 20000 --tile-size 20 --group 1 --out world
case_ "--terrain /dev/zero" 1 "a device, not a regular file" 60 -- "$sylva" forest --terrain /dev/zero --quiet
case_ "--terrain naming a FIFO" 1 "FIFO" 20 -- "$sylva" forest --terrain pipe --quiet
case_ "--budget-mb 100000" 2 "expected 1 to 128" 60 -- "$sylva" forest --area 50 --budget-mb 100000 --quiet
case_ "17 --species" 2 "at most 16" 60 -- "$sylva" forest --area 50 $(for _ in $(seq 17); do printf -- '--species oak '; done) --quiet
case_ "--out /dev/null" 1 "a device, not a regular file" 120 -- "$sylva" forest --area 50 --out /dev/null --quiet
case_ "--out X --heightmap X" 2 "both name" 60 -- "$sylva" forest --area 50 --out same.glb --heightmap same.glb --quiet
case_ "a species named with 300 KB" 1 "more than the limit of 256" 60 -- "$sylva" forest --area 50 --species long.species --quiet
test -c /dev/null || { echo "  FAILED: /dev/null is no longer a device" >&2; failures=$((failures + 1)); }

# A link to a file is written through: the target is the forest, the link stays.
"$sylva" forest --area 50 --out link.glb --heightmap link.png --quiet || failures=$((failures + 1))
if [ ! -L link.glb ] || [ ! -s forest_target.glb ]; then
  echo "  FAILED: writing through a link" >&2
  failures=$((failures + 1))
fi
# Two runs writing one path at once both succeed, and leave no scratch file.
"$sylva" forest --area 100 --out two.glb --heightmap two_a.png --quiet & first=$!
"$sylva" forest --area 100 --out two.glb --heightmap two_b.png --quiet || failures=$((failures + 1))
wait "$first" || failures=$((failures + 1))
if ls -a | grep -q 'sylva-'; then
  echo "  FAILED: scratch files left: $(ls -a | grep 'sylva-')" >&2
  failures=$((failures + 1))
fi
echo "$failures failures"
[ "$failures" = 0 ]
