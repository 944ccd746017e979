#!/usr/bin/env python3
"""Writes the OBJ files of the numerical hard cases in scenes/hard/ that come from
files: far_layers_front.obj, far_layers_back.obj, uv_sphere.obj and merged_city.obj. Deterministic: running it
again gives the same files.

    python3 scripts/make_hard_cases.py        # from the repository root
"""
import math
import pathlib

HARD = pathlib.Path(__file__).resolve().parent.parent / "scenes" / "hard"


def write(name, comment, vertices, faces, number):
    with open(HARD / name, "w", newline="\n") as out:
        for line in comment.strip().splitlines():
            out.write("# " + line.strip() + "\n")
        for v in vertices:
            out.write("v " + " ".join(number % c for c in v) + "\n")
        for f in faces:
            out.write("f " + " ".join(str(i) for i in f) + "\n")


def far_layers():
    """A unit square and, 0.5 micrometres behind it, a wider triangle, 1e5 from the origin."""
    x, y, z = 100000.0, 0.0, 100000.0
    square = [(x - 0.5, y - 0.5, z), (x + 0.5, y - 0.5, z), (x + 0.5, y + 0.5, z), (x - 0.5, y + 0.5, z)]
    behind = z - 5e-7
    triangle = [(x - 1.1, y - 0.8, behind), (x + 1.25, y - 0.65, behind), (x - 0.15, y + 1.05, behind)]
    write("far_layers_front.obj", """
        Hard case far_layers: a unit square at z = 100000, about 1e5 from the origin
        (scripts/make_hard_cases.py); far_layers_back.obj lies 0.5 micrometres behind it.
        """, square, [(1, 2, 3), (1, 3, 4)], "%.10f")
    write("far_layers_back.obj", """
        Hard case far_layers: a triangle 0.5 micrometres behind far_layers_front.obj's square,
        about 1e5 from the origin (scripts/make_hard_cases.py). A float has a step of 0.0078
        there, so read as floats the two are one plane; as doubles (a step of 1.5e-11) they
        are 5e-7 apart and the square hides the triangle wherever both are seen.
        """, triangle, [(1, 2, 3)], "%.10f")


def uv_sphere():
    """A UV sphere as an exporter writes it: six decimals, each quad split into two triangles."""
    segments, rings = 24, 12
    vertices = [(0.0, 1.0, 0.0)]
    for ring in range(1, rings):
        theta = math.pi * ring / rings
        for segment in range(segments):
            phi = 2 * math.pi * segment / segments
            vertices.append((math.sin(theta) * math.cos(phi), math.cos(theta), -math.sin(theta) * math.sin(phi)))
    vertices.append((0.0, -1.0, 0.0))
    south = len(vertices)

    def at(ring, segment):  # 1-based index of ring 1..rings-1
        return 2 + (ring - 1) * segments + segment % segments

    faces = []
    for s in range(segments):
        faces.append((1, at(1, s), at(1, s + 1)))
        for ring in range(1, rings - 1):
            a, b, c, d = at(ring, s), at(ring + 1, s), at(ring + 1, s + 1), at(ring, s + 1)
            faces += [(a, b, c), (a, c, d)]
        faces.append((south, at(rings - 1, s + 1), at(rings - 1, s)))
    write("uv_sphere.obj", """
        Hard case uv_sphere: a unit UV sphere of 24 segments and 12 rings, each quad split
        into two triangles, written with six decimals as exporters write them
        (scripts/make_hard_cases.py). Each quad is flat, but only to those six decimals: its
        two triangles' planes differ by up to about 1e-6, so a vertex lies that far outside a
        neighbouring face's plane. Convex up to the precision of its coordinates.
        """, vertices, faces, "%.6f")


def merged_city():
    """Boxes that pass through each other, merged into one mesh as one OBJ object."""
    state = 12345

    def uniform(lo, hi):  # a linear congruential generator: the same file everywhere
        nonlocal state
        state = (1103515245 * state + 12345) % 2**31
        return lo + (hi - lo) * state / 2**31

    vertices, faces = [], []
    for row in range(5):
        for column in range(5):
            cx, cz = column * 0.9 + uniform(-0.2, 0.2), row * 0.9 + uniform(-0.2, 0.2)
            hx, hz, height = uniform(0.4, 0.6), uniform(0.4, 0.6), uniform(0.6, 2.4)
            base = uniform(-0.3, 0.0)
            first = len(vertices) + 1
            for c in range(8):
                vertices.append((cx + (hx if c & 1 else -hx), base + (height if c & 2 else 0.0), cz + (hz if c & 4 else -hz)))
            for a, b, c, d in ((0, 4, 6, 2), (1, 3, 7, 5), (0, 1, 5, 4), (2, 6, 7, 3), (0, 2, 3, 1), (4, 5, 7, 6)):
                faces += [(first + a, first + b, first + c), (first + a, first + c, first + d)]
    write("merged_city.obj", """
        Hard case merged_city: 25 boxes on a jittered grid 0.9 apart, each about 1 wide, so
        neighbours pass through each other, merged into one closed mesh (every edge in two
        triangles) as one object (scripts/make_hard_cases.py). Each box is wound
        counter-clockwise from outside; the mesh passes through itself along every overlap.
        """, vertices, faces, "%.6f")


far_layers()
uv_sphere()
merged_city()
