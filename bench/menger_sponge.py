#!/usr/bin/env python3
"""Writes the surface of a Menger sponge of a given level as a closed triangle mesh (.off).

The sponge of level n is the union of the cubes of a 3^n grid whose base-3 digits never have two 1s in one place.
Its surface is made of the faces between a cube of the sponge and one outside it, each cut into two triangles and
oriented outwards. At level 3 it has genus 1409, 15232 vertices and 36096 triangles: a part of genus in the thousands, for
bench/README.md's "genus in the thousands" run.

    bench/menger_sponge.py 3 -o /tmp/menger3.off
"""

import argparse
import os
import sys
import tempfile


def inside(level, x, y, z):
    n = 3 ** level
    if not (0 <= x < n and 0 <= y < n and 0 <= z < n):
        return False
    for _ in range(level):
        if [x % 3, y % 3, z % 3].count(1) >= 2:
            return False
        x, y, z = x // 3, y // 3, z // 3
    return True


# The four corners of each face of the unit cube at the origin, counter-clockwise seen from outside, with the
# direction of the neighbour across it.
FACES = [
    ((1, 0, 0), [(1, 0, 0), (1, 1, 0), (1, 1, 1), (1, 0, 1)]),
    ((-1, 0, 0), [(0, 0, 0), (0, 0, 1), (0, 1, 1), (0, 1, 0)]),
    ((0, 1, 0), [(0, 1, 0), (0, 1, 1), (1, 1, 1), (1, 1, 0)]),
    ((0, -1, 0), [(0, 0, 0), (1, 0, 0), (1, 0, 1), (0, 0, 1)]),
    ((0, 0, 1), [(0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]),
    ((0, 0, -1), [(0, 0, 0), (0, 1, 0), (1, 1, 0), (1, 0, 0)]),
]


def sponge(level):
    n = 3 ** level
    index = {}
    vertices, triangles = [], []

    def vertex(p):
        if p not in index:
            index[p] = len(vertices)
            vertices.append(p)
        return index[p]

    for x in range(n):
        for y in range(n):
            for z in range(n):
                if not inside(level, x, y, z):
                    continue
                for (dx, dy, dz), corners in FACES:
                    if inside(level, x + dx, y + dy, z + dz):
                        continue
                    q = [vertex((x + cx, y + cy, z + cz)) for cx, cy, cz in corners]
                    triangles.append((q[0], q[1], q[2]))
                    triangles.append((q[0], q[2], q[3]))
    return vertices, triangles


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("level", type=int, help="level of the sponge (3: genus 1409)")
    parser.add_argument("-o", "--output", required=True, help="the mesh to write (.off)")
    args = parser.parse_args()
    if args.level < 1 or args.level > 4:
        sys.exit("menger_sponge.py: the level must be 1 to 4")
    vertices, triangles = sponge(args.level)
    euler = len(vertices) - len(triangles) // 2
    directory = os.path.dirname(os.path.abspath(args.output))
    with tempfile.NamedTemporaryFile("w", dir=directory, suffix=".off", delete=False) as out:
        out.write("OFF\n%d %d 0\n" % (len(vertices), len(triangles)))
        for v in vertices:
            out.write("%d %d %d\n" % v)
        for t in triangles:
            out.write("3 %d %d %d\n" % t)
    os.replace(out.name, args.output)
    print("%s: %d vertices, %d triangles, genus %d" % (args.output, len(vertices), len(triangles), 1 - euler // 2))


if __name__ == "__main__":
    main()
