#!/bin/bash
# Build a large model on this machine and say where its time and memory went.
#
# The model is the shipped didactic one (the same TSurf files, box and regions as
# recipes/refinements/d.toml) at finer sizes: SIZE everywhere and CURVE on the reservoir's
# surfaces (H1, H2 and the dangling fault F2). `SIZE=70 CURVE=12` makes about ten million tets.
# The recipe is written into a scratch directory (with absolute paths to the data), built from
# an empty cache with `-j JOBS` under `/usr/bin/time -v`, and the script prints:
#   - the wall time and the peak resident set of the whole command, and bytes per tet;
#   - the tets per region (from the quality table of the build's report);
#   - the node kinds' summed durations (from `--json`) and the slowest nodes.
#
# usage: benches/large/build_large.sh [SIZE] [CURVE] [JOBS] [FORMAT]
#        (defaults: 70 12 2 msh-binary; BIN overrides target/release/recipe; SCRATCH the scratch
#        directory, default a new one under /tmp, removed at the end unless KEEP=1)
set -eu
size=${1:-70}; curve=${2:-12}; jobs=${3:-2}; format=${4:-msh-binary}
here=$(cd "$(dirname "$0")" && pwd)
data=$(cd "$here/../../recipes/data/didactic" && pwd)
bin=$(realpath "${BIN:-target/release/recipe}")
scratch=${SCRATCH:-$(mktemp -d /tmp/large-model.XXXXXX)}
mkdir -p "$scratch"
cat > "$scratch/large.toml" <<EOF
[model]
name = "large"
units = "m"

[surfaces]
H1 = { file = "$data/H1_top_reservoir.ts", kind = "horizon" }
H2 = { file = "$data/H2_base_reservoir.ts", kind = "horizon" }
F1 = { file = "$data/F1_through.ts", kind = "fault" }
F2 = { file = "$data/F2_dangling.ts", kind = "fault" }

[box]
min = [500000.0, 7000000.0, -2500.0]
max = [505000.0, 7005000.0, 0.0]

[intersect]
all = ["H1", "H2", "F1", "box"]
pairs = [["F2", "H1"], ["F2", "H2"]]

[mesh]
size = $size.0

[mesh.curves]
"H1" = { size = $curve.0 }
"H2" = { size = $curve.0 }
"F2" = { size = $curve.0 }

[regions]
overburden_W = { point = [500500.0, 7001000.0, -600.0], material = 1 }
overburden_E = { point = [504000.0, 7001000.0, -600.0], material = 1 }
reservoir_W = { point = [500500.0, 7001000.0, -1191.6], material = 2 }
reservoir_E = { point = [504000.0, 7001000.0, -1264.9], material = 2 }
underburden_W = { point = [500500.0, 7001000.0, -2000.0], material = 3 }
underburden_E = { point = [504000.0, 7001000.0, -2000.0], material = 3 }

[output]
dir = "out"
formats = ["$format"]
EOF
cd "$scratch"
/usr/bin/time -v "$bin" build -j "$jobs" --json --cache-dir "$scratch/cache" large.toml \
    > report.json 2> build.log || { tail -30 build.log; exit 1; }
python3 - "$scratch" <<'PY'
import collections, json, re, sys
scratch = sys.argv[1]
log = open(f"{scratch}/build.log").read()
report = json.load(open(f"{scratch}/report.json"))
wall = re.search(r"Elapsed \(wall clock\) time \(h:mm:ss or m:ss\): (\S+)", log).group(1)
rss_kb = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", log).group(1))
cpu = float(re.search(r"User time \(seconds\): (\S+)", log).group(1)) + \
      float(re.search(r"System time \(seconds\): (\S+)", log).group(1))
tets = {}
for node in report["nodes"]:
    if node["kind"] == "tet_mesh" and node.get("counts"):
        tets[node["name"].split(":", 1)[1]] = node["counts"].get("tets", 0)
total = sum(tets.values())
print(f"wall {wall}, cpu {cpu:.1f} s, peak RSS {rss_kb / 1024:.0f} MB, "
      f"{total:,} tets ({rss_kb * 1024 / max(total, 1):.0f} B/tet)")
for r, n in sorted(tets.items()):
    print(f"  {r}: {n:,} tets")
by_kind = collections.defaultdict(lambda: [0, 0.0])
for node in report["nodes"]:
    k = by_kind[node["kind"]]
    k[0] += 1
    k[1] += node["duration_ms"] / 1000
print("node kind | nodes | summed seconds")
for kind, (n, s) in sorted(by_kind.items(), key=lambda kv: -kv[1][1]):
    if s >= 0.05:
        print(f"  {kind} | {n} | {s:.1f}")
print("slowest nodes:")
for node in sorted(report["nodes"], key=lambda n: -n["duration_ms"])[:8]:
    print(f"  {node['name']}: {node['duration_ms'] / 1000:.1f} s")
PY
du -sh "$scratch/out" "$scratch/cache" | sed 's/^/  size of /'
[ "${KEEP:-0}" = 1 ] || rm -rf "$scratch"
