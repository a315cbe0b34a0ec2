#!/bin/bash
# Mesh the six fault blocks of one level of the peer model with `recipe tetmesh`, one region at a
# time (one process each, so each peak RSS is that region's), and print per-region figures and
# the totals: tets, seconds (mesh_region only, as printed by the command), tets/s, peak RSS.
#
# usage: tet_regions.sh <regions dir from peer_regions.py> L2|L3 [extra tetmesh args]
# env:   BIN (default target/release/recipe), EXT (output format, default msh)
set -eu
dir=$1; level=$2; shift 2
bin=${BIN:-target/release/recipe}
out=$(mktemp -d)
total_tets=0; total_secs=0
for r in overburden_E overburden_W reservoir_E reservoir_W underburden_E underburden_W; do
  emb=()
  [ -f "$dir/${level}_$r.embedded.off" ] && emb=(--embed "$dir/${level}_$r.embedded.off")
  log=$( { /usr/bin/time -f "RSS %M" "$bin" tetmesh "$dir/${level}_$r.off" "${emb[@]}" \
      -o "$out/$r.${EXT:-msh}" "$@"; } 2>&1 )
  fin=$(grep Finished <<<"$log")
  tets=$(sed 's/.*: \([0-9]*\) tets.*/\1/' <<<"$fin")
  secs=$(sed 's/.* in \([0-9.]*\)s.*/\1/' <<<"$fin")
  rss=$(grep '^RSS' <<<"$log" | cut -d' ' -f2)
  quality=$(grep "^${level}_$r " <<<"$log" | tr -s ' ')
  echo "$r: $tets tets, $secs s, $(echo "$tets / $secs" | bc) tets/s, peak RSS $rss KB ($((rss * 1024 / tets)) B/tet) | $quality | ${fin##*; }"
  total_tets=$((total_tets + tets)); total_secs=$(echo "$total_secs + $secs" | bc)
done
echo "all six: $total_tets tets in $total_secs s = $(echo "$total_tets / $total_secs" | bc) tets/s"
rm -rf "$out"
