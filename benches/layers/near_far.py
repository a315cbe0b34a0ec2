"""Tet sizes near a surface and far from it, before and after a refinement: each tet's mean edge
length binned by the distance of its centroid from a surface (sampled every 10 m), for two
builds of the same model (issue 22's distance field around F2).

    python3 benches/layers/near_far.py without.msh with.msh F2
"""
import sys

import meshio
import numpy as np

BINS = [0, 25, 50, 75, 100, 150, 200, 300, 1000]
ZONES = [("within 200 m", 0, 200), ("200-600 m", 200, 600), ("beyond 600 m", 600, np.inf)]
EDGES = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)]


def load(path, surface):
    m = meshio.read(path)
    names = {(int(d), n): int(t) for n, (t, d) in m.field_data.items()}
    phys = m.cell_data["gmsh:physical"]
    tris = [(b.data, phys[i]) for i, b in enumerate(m.cells) if b.type == "triangle"]
    t = np.concatenate([c for c, _ in tris])
    tags = np.concatenate([g for _, g in tris])
    tets = np.concatenate([b.data for b in m.cells if b.type == "tetra"])
    return m.points, t[tags == names[(2, surface)]], tets


def samples(points, triangles, step=10.0):
    """Points on the triangles, about `step` apart."""
    out = []
    for t in triangles:
        a, b, c = points[t]
        n = int(max(np.linalg.norm(b - a), np.linalg.norm(c - a), np.linalg.norm(c - b)) / step) + 1
        for i in range(n + 1):
            for j in range(n + 1 - i):
                out.append(a + (b - a) * i / n + (c - a) * j / n)
    return np.array(out)


def measure(path, surface):
    """Per tet: distance of its centroid from the surface, and its mean edge length."""
    points, on, tets = load(path, surface)
    s = samples(points, on)
    centroids = points[tets].mean(1)
    size = np.mean([np.linalg.norm(points[tets[:, a]] - points[tets[:, b]], axis=1)
                    for a, b in EDGES], axis=0)
    lo, hi = s.min(0) - 1000, s.max(0) + 1000
    d = np.full(len(tets), np.inf)
    near = np.nonzero(((centroids > lo) & (centroids < hi)).all(1))[0]
    for k in range(0, len(near), 2000):
        chunk = near[k:k + 2000]
        d[chunk] = np.sqrt(((centroids[chunk, None, :] - s[None, :, :]) ** 2).sum(2)).min(1)
    return d, size


def main(without, with_, surface):
    print("| zone | refinement | tets | median edge | "
          + " | ".join(f"{BINS[i]}-{BINS[i + 1]}" for i in range(len(BINS) - 1)) + " |")
    print("|---" * (4 + len(BINS) - 1) + "|")
    measured = [(label, measure(path, surface)) for label, path in [("without", without), ("with", with_)]]
    for zone, lo, hi in ZONES:
        for label, (d, size) in measured:
            sel = (d > lo) & (d <= hi) if lo > 0 else d <= hi
            h, _ = np.histogram(size[sel], bins=BINS)
            print(f"| {zone} of {surface} | {label} | {sel.sum():,} | {np.median(size[sel]):.1f} m | "
                  + " | ".join(f"{x:,}" for x in h) + " |")


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    main(*sys.argv[1:])
