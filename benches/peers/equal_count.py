#!/usr/bin/env python3
"""Our tet mesher against Gmsh HXT (one thread and two) and TetGen on the same region boundaries,
at the same number of tets.

For each region boundary `<level>_<region>.off` (and its dangling fault `.embedded.off`) written by
`peer_regions.py`:
1. HXT meshes it alone (`Mesh.Algorithm3D = 10`, the boundary a discrete surface, the fault
   embedded), with its own sizes: it interpolates the boundary's. Its count is the target.
2. Our `--growth` is searched (bisection on the log of the count, which falls as growth rises)
   until `recipe tetmesh` makes the target count within `--tol` (5 %).
3. Rounds alternate HXT one thread, HXT two threads and ours, so each comparison is made minutes
   apart on a machine whose speed drifts; the table gives the medians. Times are each mesher's own:
   HXT's `generate(3)`, ours the `Finished` line of `recipe tetmesh` (mesh_region alone,
   optimisation and exact verification included). Reading and writing files is in neither.
4. TetGen `pq1.2/15Y` (the `tetgen` module) meshes the same triangles once, alongside.

Quality is computed here, alike for every mesher, from the tets each one wrote: the normalised
mean ratio 12 (3V)^(2/3) / sum of squared edge lengths (as `check_mesh.py`), its average and
minimum, and the smallest dihedral angle.

usage: equal_count.py REGIONS_DIR [--levels L1,L2,L3] [--regions a,b] [--rounds 3] [--tol 0.05]
                      [--bin target/release/recipe] [--json OUT.json]
"""
import argparse
import json
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

REGIONS = ("overburden_E", "overburden_W", "reservoir_E", "reservoir_W", "underburden_E",
           "underburden_W")


def read_off(path):
    with open(path) as fh:
        words = fh.read().split()
    assert words[0] == "OFF", path
    n, m = int(words[1]), int(words[2])
    pts = np.array(words[4:4 + 3 * n], dtype=float).reshape(n, 3)
    tri = np.array(words[4 + 3 * n:4 + 3 * n + 4 * m], dtype=np.int64).reshape(m, 4)[:, 1:]
    return pts, tri


def merged(boundary, embedded):
    """One point table for both files, points matched by exact coordinates (as ours does)."""
    P, F = boundary
    index = {tuple(p): i for i, p in enumerate(P)}
    pts = list(map(tuple, P))
    E = None
    if embedded is not None:
        Pe, Fe = embedded
        remap = []
        for p in map(tuple, Pe):
            if p not in index:
                index[p] = len(pts)
                pts.append(p)
            remap.append(index[p])
        E = np.asarray(remap, dtype=np.int64)[Fe]
    return np.asarray(pts, dtype=float), F, E


def quality(P, T):
    """(average and minimum normalised mean ratio, smallest dihedral in degrees)."""
    x0, x1, x2, x3 = (P[T[:, k]] for k in range(4))
    e = [x1 - x0, x2 - x0, x3 - x0, x2 - x1, x3 - x1, x3 - x2]
    det = np.einsum("ij,ij->i", e[0], np.cross(e[1], e[2]))
    s = sum(np.einsum("ij,ij->i", v, v) for v in e)
    q = 12.0 * (0.5 * np.abs(det)) ** (2.0 / 3.0) / s
    sgn = np.sign(det)[:, None]
    normals = [np.cross(x2 - x1, x3 - x1), np.cross(x3 - x0, x2 - x0),
               np.cross(x1 - x0, x3 - x0), np.cross(x2 - x0, x1 - x0)]
    normals = [n * sgn / np.linalg.norm(n, axis=1)[:, None] for n in normals]
    smallest = np.pi
    for i in range(4):
        for j in range(i + 1, 4):
            c = np.clip(np.einsum("ij,ij->i", normals[i], normals[j]), -1.0, 1.0)
            smallest = min(smallest, float(np.min(np.pi - np.arccos(c))))
    return float(q.mean()), float(q.min()), float(np.degrees(smallest))


def hxt(P, F, E, threads):
    """HXT on the region alone: (tets, seconds of generate(3), quality)."""
    import gmsh
    gmsh.initialize(["-nopopup"])
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.option.setNumber("General.NumThreads", threads)
        gmsh.option.setNumber("Mesh.Algorithm3D", 10)
        gmsh.model.add("region")
        boundary = gmsh.model.addDiscreteEntity(2)
        used_by_boundary = np.unique(F)
        on_boundary = np.zeros(len(P), dtype=bool)
        on_boundary[used_by_boundary] = True
        ids = np.arange(1, len(P) + 1)
        gmsh.model.mesh.addNodes(2, boundary, ids[on_boundary].tolist(),
                                 P[on_boundary].ravel().tolist())
        gmsh.model.mesh.addElementsByType(boundary, 2, [], (F + 1).ravel().tolist())
        gmsh.model.geo.synchronize()
        volume = gmsh.model.geo.addVolume([gmsh.model.geo.addSurfaceLoop([boundary])])
        gmsh.model.geo.synchronize()
        if E is not None and len(E):
            fault = gmsh.model.addDiscreteEntity(2)
            gmsh.model.mesh.addNodes(2, fault, ids[~on_boundary].tolist(),
                                     P[~on_boundary].ravel().tolist())
            gmsh.model.mesh.addElementsByType(fault, 2, [], (E + 1).ravel().tolist())
            gmsh.model.mesh.embed(2, [fault], 3, volume)
        t0 = time.perf_counter()
        gmsh.model.mesh.generate(3)
        seconds = time.perf_counter() - t0
        tags, coords, _ = gmsh.model.mesh.getNodes()
        order = np.argsort(tags)
        nodes = coords.reshape(-1, 3)[order]
        _, conn = gmsh.model.mesh.getElementsByType(4, volume)
        T = np.searchsorted(tags[order], conn).reshape(-1, 4)
        return len(T), seconds, quality(nodes, T)
    finally:
        gmsh.finalize()


def ours(binary, boundary, embedded, growth, keep=None):
    """`recipe tetmesh` at `growth`: (tets, seconds of mesh_region, quality or None)."""
    with tempfile.TemporaryDirectory() as tmp:
        out = keep or os.path.join(tmp, "region.msh")
        args = [binary, "tetmesh", boundary, "-o", out, "--growth", repr(growth)]
        if embedded:
            args += ["--embed", embedded]
        run = subprocess.run(args, capture_output=True, text=True)
        if run.returncode != 0:
            raise RuntimeError(run.stderr)
        line = next(l for l in (run.stdout + run.stderr).splitlines() if "Finished" in l)
        tets = int(re.search(r": (\d+) tets", line).group(1))
        seconds = float(re.search(r" in ([0-9.]+)s", line).group(1))
        import meshio
        mesh = meshio.read(out)
        T = np.vstack([c.data for c in mesh.cells if c.type == "tetra"])
        return tets, seconds, quality(np.asarray(mesh.points, dtype=float), T)


def calibrate(binary, boundary, embedded, target, tol):
    """The growth at which our count is within `tol` of `target` (or the closest found)."""
    lo, hi = 1.05, 3.0
    best = None
    for _ in range(12):
        g = (lo * hi) ** 0.5
        tets, _, _ = ours(binary, boundary, embedded, g)
        err = tets / target - 1.0
        if best is None or abs(err) < abs(best[1]):
            best = (g, err, tets)
        if abs(err) <= tol:
            break
        if err > 0:
            lo = g
        else:
            hi = g
    return best


def tetgen_run(P, F, E):
    import tetgen
    faces = F if E is None else np.vstack([F, E])
    used, inverse = np.unique(faces.ravel(), return_inverse=True)
    tg = tetgen.TetGen(P[used], inverse.reshape(-1, 3).astype(np.int32))
    # The module prints from C whatever the switches say: keep it off the table.
    sys.stdout.flush()
    saved, devnull = os.dup(1), os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, 1)
    try:
        t0 = time.perf_counter()
        nodes, elems, _, _ = tg.tetrahedralize(switches="pq1.2/15YQ")
        seconds = time.perf_counter() - t0
    finally:
        os.dup2(saved, 1)
        os.close(saved)
        os.close(devnull)
    T = np.asarray(elems)[:, :4]
    return len(T), seconds, quality(np.asarray(nodes), T)


def measure(args, level, region):
    base = os.path.join(args.regions_dir, f"{level}_{region}")
    boundary, embedded = base + ".off", base + ".embedded.off"
    if not os.path.exists(boundary):
        return None
    embedded = embedded if os.path.exists(embedded) else None
    P, F, E = merged(read_off(boundary), read_off(embedded) if embedded else None)
    target, _, hxt_q = hxt(P, F, E, 1)
    growth, err, _ = calibrate(args.bin, boundary, embedded, target, args.tol)
    times = {"hxt1": [], "hxt2": [], "ours": []}
    counts = {}
    for _ in range(args.rounds):
        for name, threads in (("hxt1", 1), ("hxt2", 2)):
            tets, seconds, q = hxt(P, F, E, threads)
            times[name].append(seconds)
            counts[name] = (tets, q)
        tets, seconds, q = ours(args.bin, boundary, embedded, growth)
        times["ours"].append(seconds)
        counts["ours"] = (tets, q)
    tg = tetgen_run(P, F, E) if args.tetgen else None
    row = dict(level=level, region=region, growth=growth, count_error=err, hxt_quality=hxt_q,
               tetgen=tg)
    for name, ts in times.items():
        row[name] = dict(tets=counts[name][0], median_s=statistics.median(ts), seconds=ts,
                         quality=counts[name][1])
    return row


def markdown(rows):
    print("| boundary | mesher | tets | median s | tets/s | avg MR | min MR | min dihedral |")
    print("|---|---|---|---|---|---|---|---|")
    for r in rows:
        name = f"{r['level']} {r['region']}"
        entries = [("ours (growth %.3f)" % r["growth"], r["ours"]),
                   ("HXT 1 thread", r["hxt1"]), ("HXT 2 threads", r["hxt2"])]
        for label, m in entries:
            avg, mn, dih = m["quality"]
            print(f"| {name} | {label} | {m['tets']:,} | {m['median_s']:.3f} | "
                  f"{m['tets'] / m['median_s'] / 1000:.0f}k | {avg:.3f} | {mn:.3f} | {dih:.1f}° |")
            name = ""
        if r["tetgen"]:
            tets, s, (avg, mn, dih) = r["tetgen"]
            print(f"| | TetGen pq1.2/15Y | {tets:,} | {s:.3f} | {tets / s / 1000:.0f}k | "
                  f"{avg:.3f} | {mn:.3f} | {dih:.1f}° |")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("regions_dir")
    ap.add_argument("--levels", default="L1,L2,L3")
    ap.add_argument("--regions", default=",".join(REGIONS))
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--tol", type=float, default=0.05)
    ap.add_argument("--bin", default="target/release/recipe")
    ap.add_argument("--no-tetgen", dest="tetgen", action="store_false")
    ap.add_argument("--json")
    args = ap.parse_args()
    rows = []
    for level in args.levels.split(","):
        for region in args.regions.split(","):
            row = measure(args, level, region)
            if row is None:
                continue
            rows.append(row)
            print(f"{level} {region}: ours {row['ours']['tets']} ({row['ours']['median_s']:.3f} s), "
                  f"HXT {row['hxt1']['tets']} ({row['hxt1']['median_s']:.3f} s, 2 threads "
                  f"{row['hxt2']['median_s']:.3f} s)", file=sys.stderr, flush=True)
    if args.json:
        with open(args.json, "w") as fh:
            json.dump(rows, fh, indent=1)
    markdown(rows)


if __name__ == "__main__":
    main()
