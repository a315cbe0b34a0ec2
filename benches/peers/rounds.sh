#!/bin/bash
# Alternate Gmsh HXT and ours in rounds, so that each comparison is made minutes apart on a
# machine whose speed drifts: each round runs `bench_peers.py` (Gmsh 2D, then HXT on one thread)
# at L1, L2 and L3, then `tet_regions.sh` on the six regions of each level, and prints one line
# per mesher and level: tets, seconds, tets/s.
#
# usage: rounds.sh <regions dir from peer_regions.py> <rounds> [out dir, default /tmp/peer-rounds]
# env:   BIN (our `recipe` binary, default target/release/recipe), PEERS (bench_peers.py, default
#        ../shared/tools/bench_peers.py)
set -eu
regions=$1; rounds=$2; out=${3:-/tmp/peer-rounds}
peers=${PEERS:-../shared/tools/bench_peers.py}
here=$(cd "$(dirname "$0")" && pwd)
for k in $(seq "$rounds"); do
  dir="$out/round_$k"; rm -rf "$dir"; mkdir -p "$dir"
  PEER_BENCH_OUT="$dir" python3 "$peers" run --levels L1,L2,L3 --only gmsh2d,gmsh3d --algos 10 \
      --threads 1 --clamp 5000 --timeout 1500 > "$dir/bench_peers.log" 2>&1
  python3 - "$dir/results_peers.json" "$k" <<'PY'
import json, sys
runs = json.load(open(sys.argv[1]))["runs"]
for key, r in sorted(runs.items()):
    if key.startswith("gmsh3d") and r.get("status") == "ok":
        level = key.split("|")[1]
        print(f"round {sys.argv[2]} {level} HXT: {r['tets']} tets in {r['mesh3d_s']:.2f} s = "
              f"{r['tets'] / r['mesh3d_s']:.0f} tets/s")
PY
  for level in L1 L2 L3; do
    echo "round $k $level ours: $(bash "$here/tet_regions.sh" "$regions" "$level" | tail -1 | sed 's/^all six: //')"
  done
done
