#!/usr/bin/env python3
"""Our surface mesher versus Gmsh's 2D mesher on the SAME curve discretization (issue 5).

Reads the per-patch dumps written by `SQ_DUMP=DIR cargo run --release --example surface_quality
-- RECIPE CACHE` (one `<patch>.txt` per patch: header, our mesh, the discretized loops and
constraints, the support), re-meshes every planar patch with Gmsh, and prints c/c* statistics
(c/c* = sum of squared edge lengths / (4*sqrt(3)*area), 1 for an equilateral triangle) per
surface kind and overall, ours and Gmsh's side by side, plus the meshing throughput of each.

Gmsh gets exactly our curve nodes: one geometry point per node, one straight line per segment,
each line transfinite with 2 nodes (Gmsh adds no node on our curves), one plane surface per patch
(largest loop outer, the others holes), the constraints embedded. Mesh size at a point = mean
length of its segments; Mesh.MeshSizeExtendFromBoundary=1, Mesh.MeshSizeMax = the surface's
target size, Mesh.Algorithm=6 (Frontal-Delaunay), one thread. Only `generate(2)` is timed (the
trivial 1D mesh is generated before). Gmsh meshes the patch in a local frame whose third axis is
the patch's normal, its points projected on the plane (F1 and F2 are planar to 0.5 mm, the
coordinates' rounding; Gmsh's own mean plane of the raw points was off by metres). After meshing,
the script checks that the nodes Gmsh holds on curves are exactly our curve nodes (one per point,
each within 1e-9 of the patch diameter in the plane, none inside a segment), gives them back
their exact coordinates, and that both meshes cover the same area (1e-6 relative); it refuses the comparison
otherwise.

Curved patches (the horizons H1, H2, dipping at most ~5 degrees) have no CAD Gmsh could
reparametrise, and a discrete surface classified from our support would get Gmsh's own boundary
curves, not our discretization. When the support is a height field z = f(x, y), the script gives
Gmsh the patch projected on the horizontal plane (the same curve nodes, sizes = 3D segment
lengths) and lifts Gmsh's interior nodes onto the support (linear on its triangles); c/c* of both
meshes is measured in 3D. That is Gmsh meshing in the (x, y) parametrisation, as it does any
parametric surface, without its anisotropic correction for the slope (under 0.4 % in length at 5
degrees). The coverage check then compares areas projected on the horizontal plane. Rows `planar`
aggregate the planar patches only; `all` adds the lifted horizons. Patches that are neither
planar nor a height field are skipped and counted.

Variant `--graded R`: instead of MeshSizeExtendFromBoundary (which interpolates the curve sizes
across the whole patch, so a patch bounded by fine curves stays fine inside), Gmsh's sizes come
from an Extend field on all the patch's curves: the curve size growing linearly with the distance
by R per unit length up to the surface's size, as ours grows (R = 0.15: MAX_SURFACE_GROWTH - 1).

usage: gmsh_same_curves.py DUMP_DIR [--label NAME] [--markdown] [--repeat N] [--graded R]
"""

import argparse
import math
import os
import sys
import time

import numpy as np

try:
    import gmsh
except ImportError:  # pragma: no cover
    sys.exit("the python module `gmsh` is required (pip install gmsh)")


class Patch:
    def __init__(self, name):
        self.name = name
        self.surface = None
        self.size = None
        self.secs = None
        self.n_loops = None
        self.n_constraints = None
        self.verts = []
        self.tris = []
        self.curves = []  # loops first, then constraints
        self.support_v = []
        self.support_t = []

    @property
    def loops(self):
        return self.curves[: self.n_loops]

    @property
    def constraints(self):
        return self.curves[self.n_loops :]


def read_dump(path):
    """Parses one dump file; raises ValueError naming the file and line on bad input."""
    p = Patch(os.path.splitext(os.path.basename(path))[0])
    cur = []
    with open(path) as f:
        for ln, line in enumerate(f, 1):
            w = line.split()
            if not w:
                continue
            try:
                k = w[0]
                if k == "v":
                    p.verts.append([float(x) for x in w[1:4]])
                elif k == "t":
                    p.tris.append([int(x) for x in w[1:4]])
                elif k == "l":
                    cur.append(tuple(float(x) for x in w[1:4]))
                elif k == "e":
                    p.curves.append(cur)
                    cur = []
                elif k == "surface":
                    p.surface = w[1]
                elif k == "size":
                    p.size = float(w[1])
                elif k == "secs":
                    p.secs = float(w[1])
                elif k == "loops":
                    p.n_loops = int(w[1])
                    p.n_constraints = int(w[3])
                elif k == "sv":
                    p.support_v.append([float(x) for x in w[1:4]])
                elif k == "st":
                    p.support_t.append([int(x) for x in w[1:4]])
                else:
                    raise ValueError(f"unknown record `{k}`")
            except (ValueError, IndexError) as e:
                raise ValueError(f"{path}:{ln}: {e}") from None
    if p.n_loops is None or p.surface is None or p.size is None or p.secs is None:
        raise ValueError(
            f"{path}: no header (surface/size/secs/loops); re-dump with the current "
            "examples/surface_quality.rs"
        )
    if len(p.curves) != p.n_loops + p.n_constraints:
        raise ValueError(
            f"{path}: header says {p.n_loops} loops + {p.n_constraints} constraints, "
            f"found {len(p.curves)} curves"
        )
    return p


def curve_points(p):
    return np.array([q for c in p.curves for q in c], dtype=float)


def is_planar(p, rel=1e-6):
    """All curve nodes within rel * diameter of their least-squares plane."""
    pts = curve_points(p)
    c = pts.mean(axis=0)
    d = pts - c
    _, s, vt = np.linalg.svd(d, full_matrices=False)
    normal = vt[2]
    diam = np.linalg.norm(pts.max(axis=0) - pts.min(axis=0))
    return np.abs(d @ normal).max() <= rel * diam, normal


def c_ratios(verts, tris):
    v = np.asarray(verts, dtype=float)
    t = np.asarray(tris, dtype=np.int64)
    a, b, c = v[t[:, 0]], v[t[:, 1]], v[t[:, 2]]
    s = ((b - a) ** 2).sum(1) + ((c - a) ** 2).sum(1) + ((c - b) ** 2).sum(1)
    area = 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1)
    with np.errstate(divide="ignore"):
        return np.where(area > 0, s / (4.0 * math.sqrt(3.0) * area), np.inf)


def plane_frame(normal):
    """Rows e1, e2, n: an orthonormal frame whose third axis is the unit `normal`."""
    n = normal / np.linalg.norm(normal)
    helper = np.eye(3)[int(np.argmin(np.abs(n)))]
    e1 = np.cross(n, helper)
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(n, e1)
    return np.array([e1, e2, n])


def projected_area(verts, tris, normal):
    """Sum of the triangles' areas projected on the plane of `normal` (signed, then absolute)."""
    v = np.asarray(verts, dtype=float)
    t = np.asarray(tris, dtype=np.int64)
    a, b, c = v[t[:, 0]], v[t[:, 1]], v[t[:, 2]]
    return abs(float((np.cross(b - a, c - a) @ normal).sum()) / 2.0)


def height_field(p):
    """True when the support is a graph z = f(x, y): every support triangle's normal within
    about 84 degrees of the vertical, all on the same side."""
    if not p.support_t:
        return False
    v = np.asarray(p.support_v, dtype=float)
    t = np.asarray(p.support_t, dtype=np.int64)
    n = np.cross(v[t[:, 1]] - v[t[:, 0]], v[t[:, 2]] - v[t[:, 0]])
    nz = n[:, 2] / np.linalg.norm(n, axis=1)
    return bool((nz > 0.1).all() or (nz < -0.1).all())


def lift(p, xy):
    """z of the support (linear on its triangles) above each (x, y); raises if one is outside."""
    v = np.asarray(p.support_v, dtype=float)
    t = np.asarray(p.support_t, dtype=np.int64)
    a, b, c = v[t[:, 0]], v[t[:, 1]], v[t[:, 2]]
    det = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (c[:, 0] - a[:, 0]) * (b[:, 1] - a[:, 1])
    span = np.abs(v[:, :2].max(axis=0) - v[:, :2].min(axis=0)).max()
    out = np.empty(len(xy))
    for i, (x, y) in enumerate(xy):
        l1 = ((x - a[:, 0]) * (c[:, 1] - a[:, 1]) - (c[:, 0] - a[:, 0]) * (y - a[:, 1])) / det
        l2 = ((b[:, 0] - a[:, 0]) * (y - a[:, 1]) - (x - a[:, 0]) * (b[:, 1] - a[:, 1])) / det
        l0 = 1.0 - l1 - l2
        worst = np.minimum(np.minimum(l0, l1), l2)
        k = int(np.argmax(worst))
        if worst[k] < -1e-9 * span:
            raise RuntimeError(f"{p.name}: Gmsh node ({x}, {y}) is off the support")
        out[i] = l0[k] * a[k, 2] + l1[k] * b[k, 2] + l2[k] * c[k, 2]
    return out


def loop_area(loop, normal):
    """Area of a closed loop projected on the plane of `normal` (absolute)."""
    pts = np.array(loop)
    c = pts.mean(axis=0)
    tot = np.zeros(3)
    for i in range(len(pts)):
        tot += np.cross(pts[i] - c, pts[(i + 1) % len(pts)] - c)
    return abs(tot @ normal) / 2.0


def gmsh_patch(p, normal, lifted=False, repeat=1, graded=None):
    """Meshes patch p with Gmsh on our curve nodes, in the plane of `normal`; with `lifted`, the
    plane is horizontal and Gmsh's interior nodes are lifted onto the support afterwards.
    With `repeat`, meshes that many times and keeps the fastest time. With `graded` (a rate
    per unit length), sizes come from an Extend field instead of MeshSizeExtendFromBoundary.
    Returns (verts, tris, secs, n_curve_nodes)."""
    pts = curve_points(p)
    # A local orthonormal frame with the plane's normal as third axis: UTM coordinates waste
    # Gmsh's tolerances, and Gmsh's own mean plane of a tilted patch can be off by metres (its
    # interior nodes then leave the plane). A rotation changes no c/c*.
    origin = pts.mean(axis=0)
    frame = plane_frame(normal)
    diam = float(np.linalg.norm(pts.max(axis=0) - pts.min(axis=0)))

    # One point per distinct node (a constraint end on a loop is the loop's node).
    index = {}
    coords = []
    seglen = []
    curves_ids = []
    for c in p.curves:
        ids = []
        for q in c:
            if q not in index:
                index[q] = len(coords)
                coords.append(q)
                seglen.append([])
            ids.append(index[q])
        curves_ids.append(ids)
    segs = []
    for k, ids in enumerate(curves_ids):
        closed = k < p.n_loops
        n = len(ids)
        pairs = [(ids[i], ids[(i + 1) % n]) for i in range(n if closed else n - 1)]
        segs.append(pairs)
        for a, b in pairs:
            l = math.dist(coords[a], coords[b])
            seglen[a].append(l)
            seglen[b].append(l)

    gmsh.clear()
    gmsh.model.add(p.name)
    geo = gmsh.model.geo
    ptag = []
    for q, ls in zip(coords, seglen):
        x, y, _ = frame @ (np.array(q) - origin)
        ptag.append(geo.addPoint(x, y, 0.0, sum(ls) / len(ls)))
    line_of = {}
    curve_lines = []
    for pairs in segs:
        lines = []
        for a, b in pairs:
            if (a, b) in line_of:
                lines.append(line_of[(a, b)])
            elif (b, a) in line_of:
                lines.append(-line_of[(b, a)])
            else:
                t = geo.addLine(ptag[a], ptag[b])
                line_of[(a, b)] = t
                lines.append(t)
        curve_lines.append(lines)
    loops = list(range(p.n_loops))
    loops.sort(key=lambda k: -loop_area(p.curves[k], normal))
    cl = [geo.addCurveLoop(curve_lines[k]) for k in loops]
    surf = geo.addPlaneSurface(cl)
    for t in line_of.values():
        geo.mesh.setTransfiniteCurve(t, 2)
    geo.synchronize()
    emb = sorted({abs(t) for k in range(p.n_loops, len(p.curves)) for t in curve_lines[k]})
    if emb:
        gmsh.model.mesh.embed(1, emb, 2, surf)

    gmsh.option.setNumber("Mesh.MeshSizeMax", p.size)
    if graded is None:
        gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 1)
    else:
        # Sizes from the curve segments, growing linearly with the distance from the curves by
        # `graded` per unit length up to the surface's size (Gmsh's Extend field).
        gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
        hmin = min(min(ls) for ls in seglen)
        f = gmsh.model.mesh.field.add("Extend")
        gmsh.model.mesh.field.setNumbers(f, "CurvesList", sorted(line_of.values()))
        gmsh.model.mesh.field.setNumbers(f, "SurfacesList", [surf])
        gmsh.model.mesh.field.setNumber(f, "DistMax", max(p.size - hmin, 1e-3 * p.size) / graded)
        gmsh.model.mesh.field.setNumber(f, "SizeMax", p.size)
        gmsh.model.mesh.field.setNumber(f, "Power", 1.0)
        gmsh.model.mesh.field.setAsBackgroundMesh(f)
    gmsh.option.setNumber("Mesh.Algorithm", 6)
    gmsh.option.setNumber("General.NumThreads", 1)
    secs = math.inf
    for _ in range(max(1, repeat)):
        gmsh.model.mesh.clear()
        gmsh.model.mesh.generate(1)
        t0 = time.perf_counter()
        gmsh.model.mesh.generate(2)
        secs = min(secs, time.perf_counter() - t0)

    tags, xyz, _ = gmsh.model.mesh.getNodes()
    local = xyz.reshape(-1, 3)
    xyz = local @ frame + origin
    pos = {int(t): i for i, t in enumerate(tags)}
    etypes, _, enodes = gmsh.model.mesh.getElements(2, surf)
    tris = []
    for et, en in zip(etypes, enodes):
        if et != 2:
            raise RuntimeError(f"{p.name}: Gmsh made element type {et}, not triangles")
        tris = [[pos[int(a)] for a in en[i : i + 3]] for i in range(0, len(en), 3)]

    # Boundary check: Gmsh must hold exactly one node per geometry point (our curve nodes), in
    # place, and none inside a line; its boundary edges are exactly our loop segments. Those nodes then get our exact coordinates back (Gmsh saw
    # them projected on the plane, at most the planarity tolerance away).
    for _, tag in gmsh.model.getEntities(1):
        nt, _, _ = gmsh.model.mesh.getNodes(1, tag, includeBoundary=False)
        if len(nt):
            raise RuntimeError(f"{p.name}: Gmsh added {len(nt)} nodes inside segment {tag}")
    point_of_tag = {t: i for i, t in enumerate(ptag)}
    seen = 0
    node_of = {}
    on_points = []
    for _, tag in gmsh.model.getEntities(0):
        nt, _, _ = gmsh.model.mesh.getNodes(0, tag)
        on_points.extend(nt)
        if len(nt) != 1 or tag not in point_of_tag:
            raise RuntimeError(f"{p.name}: Gmsh point {tag} holds {len(nt)} nodes")
        i = pos[int(nt[0])]
        ours = np.array(coords[point_of_tag[tag]])
        err = np.abs((ours - origin) @ frame.T - local[i])[:2].max()
        if err > 1e-9 * diam:
            raise RuntimeError(f"{p.name}: Gmsh moved curve node {ours} by {err:g}")
        xyz[i] = ours
        node_of[point_of_tag[tag]] = i
        seen += 1
    if seen != len(coords):
        raise RuntimeError(f"{p.name}: Gmsh has {seen} nodes on curves, ours {len(coords)}")
    # Every loop segment is a boundary edge of Gmsh's mesh and nothing else is; every constraint
    # segment is an inner edge.
    uses = {}
    for t in tris:
        for k in range(3):
            e = tuple(sorted((t[k], t[(k + 1) % 3])))
            uses[e] = uses.get(e, 0) + 1
    for k, pairs in enumerate(segs):
        want = 1 if k < p.n_loops else 2
        for a, b in pairs:
            e = tuple(sorted((node_of[a], node_of[b])))
            if uses.get(e, 0) != want:
                raise RuntimeError(
                    f"{p.name}: segment {coords[a]}-{coords[b]} is in {uses.get(e, 0)} "
                    f"Gmsh triangles, expected {want}"
                )
    n_loop_segs = sum(len(pairs) for pairs in segs[: p.n_loops])
    if sum(1 for u in uses.values() if u == 1) != n_loop_segs:
        raise RuntimeError(f"{p.name}: Gmsh's mesh has a boundary edge that is not ours")
    if lifted:
        inner = sorted(set(range(len(xyz))) - set(pos[int(t)] for t in on_points))
        xyz[inner, 2] = lift(p, xyz[inner, :2])
    return xyz, tris, secs, len(coords)


def kind_of(surface):
    s = surface.lower()
    if s.startswith("box"):
        return "box"
    return surface


def stats(q, secs):
    n = len(q)
    if n == 0:
        return None
    return {
        "tris": n,
        "avg": float(q.mean()),
        "sd": float(q.std()),
        "max": float(q.max()),
        "p115": 100.0 * float((q > 1.15).mean()),
        "p15": 100.0 * float((q > 1.5).mean()),
        "rate": n / secs if secs > 0 else float("inf"),
    }


def fmt_row(name, side, s, md):
    cells = [
        name,
        side,
        f"{s['tris']}",
        f"{s['avg']:.4f}",
        f"{s['sd']:.4f}",
        f"{s['max']:.3f}",
        f"{s['p115']:.2f}",
        f"{s['p15']:.2f}",
        f"{s['rate']:.0f}",
    ]
    if md:
        return "| " + " | ".join(cells) + " |"
    return "{:<12} {:<5} {:>7} {:>8} {:>7} {:>7} {:>7} {:>7} {:>9}".format(*cells)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("dump_dir")
    ap.add_argument("--label", default="")
    ap.add_argument("--markdown", action="store_true")
    ap.add_argument(
        "--graded",
        type=float,
        default=None,
        help="Gmsh variant: size grows from the curves by this rate per unit length (Extend field)",
    )
    ap.add_argument("--repeat", type=int, default=1, help="time each patch N times, keep the fastest")
    args = ap.parse_args()

    files = sorted(f for f in os.listdir(args.dump_dir) if f.endswith(".txt"))
    if not files:
        sys.exit(f"{args.dump_dir}: no patch dumps (*.txt)")
    gmsh.initialize(["gmsh", "-v", "0"])  # quiet, no argv from this script
    gmsh.option.setNumber("General.Terminal", 0)
    acc = {}  # kind -> dict(side -> [qualities], secs)
    skipped = []
    checked_nodes = 0
    for f in files:
        p = read_dump(os.path.join(args.dump_dir, f))
        planar, normal = is_planar(p)
        lifted = not planar
        if lifted:
            if not height_field(p):
                skipped.append((p.name, p.surface))
                continue
            normal = np.array([0.0, 0.0, 1.0])
        gv, gt, gsecs, nb = gmsh_patch(p, normal, lifted, args.repeat, args.graded)
        checked_nodes += nb
        qo = c_ratios(p.verts, p.tris)
        qg = c_ratios(gv, gt)
        ao, ag = projected_area(p.verts, p.tris, normal), projected_area(gv, gt, normal)
        if abs(ao - ag) > 1e-6 * ao:
            raise RuntimeError(f"{p.name}: our mesh covers {ao:.6g} m2, Gmsh's {ag:.6g} m2")
        for k in (kind_of(p.surface), "all") if lifted else (kind_of(p.surface), "planar", "all"):
            a = acc.setdefault(k, {"ours": [], "gmsh": [], "ours_s": 0.0, "gmsh_s": 0.0, "n": 0})
            a["ours"].append(qo)
            a["gmsh"].append(qg)
            a["ours_s"] += p.secs
            a["gmsh_s"] += gsecs
            a["n"] += 1
    gmsh.finalize()

    md = args.markdown
    head = ["kind", "mesh", "tris", "avg", "SD", "max", "%>1.15", "%>1.5", "tris/s"]
    if args.label:
        print(f"{'### ' if md else ''}{args.label}\n")
    if md:
        print("| " + " | ".join(head) + " |")
        print("|" + "---|" * len(head))
    else:
        print("{:<12} {:<5} {:>7} {:>8} {:>7} {:>7} {:>7} {:>7} {:>9}".format(*head))
    order = sorted(k for k in acc if k not in ("planar", "all")) + ["planar", "all"]
    for k in order:
        if k not in acc:
            continue
        a = acc[k]
        for side in ("ours", "gmsh"):
            s = stats(np.concatenate(a[side]), a[side + "_s"])
            print(fmt_row(f"{k} ({a['n']})" if side == "ours" else "", side, s, md))
    print()
    print(
        f"{acc.get('all', {}).get('n', 0)} patches meshed by both "
        f"({acc.get('planar', {}).get('n', 0)} planar); Gmsh kept all "
        f"{checked_nodes} of our curve nodes and added none on the curves."
    )
    if skipped:
        names = ", ".join(sorted({s for _, s in skipped}))
        print(f"{len(skipped)} curved patches skipped (surfaces: {names}).")


if __name__ == "__main__":
    main()
