"""Elements across a layer, as issue 22 counts them: for each region named, the fewest tet edges
from any node on surface TOP to any node on surface BOTTOM through the region's tets (a
breadth-first search over the edges of a recipe's .msh, read with meshio).

    python3 benches/layers/across.py out/didactic/didactic.msh H1 H2 reservoir_W reservoir_E
"""
import sys

import meshio
import numpy as np

EDGES = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)]


def groups(mesh):
    """(dim, name) -> physical tag, and the physical tag of each cell block."""
    names = {(int(dim), name): int(tag) for name, (tag, dim) in mesh.field_data.items()}
    return names, mesh.cell_data["gmsh:physical"]


def cells(mesh, kind, phys):
    blocks = [(b.data, phys[i]) for i, b in enumerate(mesh.cells) if b.type == kind]
    return np.concatenate([c for c, _ in blocks]), np.concatenate([t for _, t in blocks])


def main(path, top, bottom, regions):
    mesh = meshio.read(path)
    names, phys = groups(mesh)
    tris, tri_tags = cells(mesh, "triangle", phys)
    tets, tet_tags = cells(mesh, "tetra", phys)
    n = len(mesh.points)

    def on(surface):
        mask = np.zeros(n, bool)
        mask[tris[tri_tags == names[(2, surface)]].ravel()] = True
        return mask

    start, goal = on(top), on(bottom)
    for region in regions:
        t = tets[tet_tags == names[(3, region)]]
        e = np.concatenate([t[:, [a, b]] for a, b in EDGES])
        e = np.unique(np.sort(e, 1), axis=0)
        e = np.concatenate([e, e[:, ::-1]])
        inside = np.zeros(n, bool)
        inside[t.ravel()] = True
        dist = np.full(n, -1)
        front = np.nonzero(start & inside)[0]
        dist[front] = 0
        level = 0
        while len(front) and not goal[front].any() and level < 16:
            reached = np.unique(e[np.isin(e[:, 0], front), 1])
            front = reached[dist[reached] < 0]
            level += 1
            dist[front] = level
        hit = np.nonzero(goal & inside & (dist >= 0))[0]
        fewest = dist[hit].min() if len(hit) else None
        at = np.count_nonzero(dist[hit] == fewest) if fewest is not None else 0
        print(f"{region}: {len(t):,} tets; fewest edges {top} -> {bottom}: {fewest} "
              f"({at:,} of {np.count_nonzero(goal & inside):,} {bottom} nodes at that distance)")


if __name__ == "__main__":
    if len(sys.argv) < 5:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:])
