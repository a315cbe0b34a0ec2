#!/bin/bash
# Full build versus builds where nothing changed, for every shipped recipe and for one or more
# `recipe` binaries (say, before and after a change), in alternating rounds so that a machine
# whose speed drifts affects every binary alike. Each round, for each recipe and each binary: a
# full build into an empty cache and output directory, then the same build twice (the first
# writes the report again, its steps being cached now; the second is the steady no-op build).
# Prints one line per build, then the medians per recipe and binary with each no-op build as a
# percentage of the full build.
#
# usage: noop_rounds.sh <rounds> <binary>...     (e.g. 5 /tmp/recipe-main target/release/recipe)
set -eu
rounds=$1; shift
here=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cp -r "$here/recipes/data" "$work/data"
mkdir -p "$work/refinements"
cp "$here"/recipes/*.toml "$work/"
cp "$here"/recipes/refinements/*.toml "$work/refinements/"
recipes="didactic.toml refinements/a.toml refinements/b.toml refinements/c.toml refinements/d.toml"
# Seconds taken by `recipe build --quiet` of $2 with binary $1 and cache $3.
timed() {
  local t0=${EPOCHREALTIME/[.,]/}
  (cd "$work" && "$1" build --quiet --cache-dir "$3" "$2" 2>/dev/null)
  local us=$(( ${EPOCHREALTIME/[.,]/} - t0 ))
  printf '%d.%06d\n' $((us / 1000000)) $((us % 1000000))
}
log=$work/log
for k in $(seq "$rounds"); do
  for r in $recipes; do
    for b in "$@"; do
      rm -rf "$work/cache" "$work/out"
      full=$(timed "$b" "$r" cache); first=$(timed "$b" "$r" cache); steady=$(timed "$b" "$r" cache)
      echo "round $k $r $b full $full first $first steady $steady" | tee -a "$log"
    done
  done
done
python3 - "$log" <<'PY'
import statistics, sys
runs = {}
for line in open(sys.argv[1]):
    w = line.split()
    runs.setdefault((w[2], w[3]), []).append((float(w[5]), float(w[7]), float(w[9])))
print(f"{'recipe':<22} {'binary':<28} {'full s':>7} {'no-op s':>8} {'%':>5} {'steady s':>9} {'%':>5}")
for (r, b), v in runs.items():
    full, first, steady = (statistics.median(x[i] for x in v) for i in range(3))
    print(f"{r:<22} {b[-28:]:<28} {full:7.2f} {first:8.3f} {100*first/full:5.1f} "
          f"{steady:9.3f} {100*steady/full:5.1f}")
PY
