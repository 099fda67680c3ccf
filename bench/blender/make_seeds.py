#!/usr/bin/env python3
"""Write N seed points uniformly distributed inside a closed triangle mesh (OBJ).

usage: make_seeds.py MESH.obj OUT.xyz [N=100] [SEED=1]

Rejection sampling in the mesh's bounding box; a candidate is kept when the
generalized winding number of the mesh around it (sum of the triangles' signed
solid angles / 4 pi, van Oosterom-Strackee) is above 0.5. That needs only
consistently wound triangles, so the unwelded vertices of an exported OBJ are fine.
Plain Python (no numpy); deterministic for a given SEED.
"""
import math
import random
import sys


def read_obj(path):
    verts, tris = [], []
    with open(path) as f:
        for line in f:
            parts = line.split()
            if not parts:
                continue
            if parts[0] == "v":
                verts.append(tuple(float(c) for c in parts[1:4]))
            elif parts[0] == "f":
                idx = [int(p.split("/")[0]) for p in parts[1:]]
                idx = [i - 1 if i > 0 else len(verts) + i for i in idx]
                for k in range(1, len(idx) - 1):  # fan-triangulate polygons
                    tris.append((verts[idx[0]], verts[idx[k]], verts[idx[k + 1]]))
    return verts, tris


def winding_number(p, tris):
    px, py, pz = p
    total = 0.0
    for a, b, c in tris:
        ax, ay, az = a[0] - px, a[1] - py, a[2] - pz
        bx, by, bz = b[0] - px, b[1] - py, b[2] - pz
        cx, cy, cz = c[0] - px, c[1] - py, c[2] - pz
        la = math.sqrt(ax * ax + ay * ay + az * az)
        lb = math.sqrt(bx * bx + by * by + bz * bz)
        lc = math.sqrt(cx * cx + cy * cy + cz * cz)
        det = (ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx)
               + az * (bx * cy - by * cx))
        den = (la * lb * lc + (ax * bx + ay * by + az * bz) * lc
               + (bx * cx + by * cy + bz * cz) * la
               + (cx * ax + cy * ay + cz * az) * lb)
        total += 2.0 * math.atan2(det, den)
    return total / (4.0 * math.pi)


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    mesh, out = sys.argv[1], sys.argv[2]
    n = int(sys.argv[3]) if len(sys.argv) > 3 else 100
    seed = int(sys.argv[4]) if len(sys.argv) > 4 else 1
    verts, tris = read_obj(mesh)
    lo = [min(v[i] for v in verts) for i in range(3)]
    hi = [max(v[i] for v in verts) for i in range(3)]
    rng = random.Random(seed)
    points, tried = [], 0
    while len(points) < n:
        p = tuple(rng.uniform(lo[i], hi[i]) for i in range(3))
        tried += 1
        if winding_number(p, tris) > 0.5:
            points.append(p)
    with open(out, "w") as f:
        f.write("# %d points uniform inside %s (make_seeds.py, seed %d, %d candidates)\n"
                % (n, mesh, seed, tried))
        for p in points:
            f.write("%.17g %.17g %.17g\n" % p)
    print("wrote %d seeds to %s (%d candidates, inside fraction %.3f)"
          % (n, out, tried, n / tried), file=sys.stderr)


if __name__ == "__main__":
    main()
