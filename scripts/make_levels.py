#!/usr/bin/env python3
"""Writes the levels divided into cells: scenes/study/indoor.toml whole (a long hall with
rooms on both sides, every wall with a door), the cells and portals at the end of
scenes/study/corridors.toml and scenes/study/castle.toml (everything after their line
"# Cells and portals"), and the
hard case scenes/hard/portal_rooms.toml (nine small rooms, doors off the middle). A
portal-culled level needs dozens of cells and hundreds of portals, each placed exactly on
a wall's centre line; written by hand they would drift from the walls they open.
Deterministic: running it again gives the same files.

    python3 scripts/make_levels.py        # from the repository root
"""
import pathlib

STUDY = pathlib.Path(__file__).resolve().parent.parent / "scenes" / "study"
MARKER = "# Cells and portals"


def number(value):
    text = ("%.4f" % value).rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def vector(values):
    return "[" + ", ".join(number(v) for v in values) + "]"


def box(name, lo, hi, color):
    """An object: a box from corner lo to corner hi."""
    size = [h - l for l, h in zip(lo, hi)]
    center = [(l + h) / 2 for l, h in zip(lo, hi)]
    return (f'[[objects]]\nname = "{name}"\nshape = "box"\nsize = {vector(size)}\n'
            f"translate = {vector(center)}\ncolor = {vector(color)}\n")


def header(comment, effects, size, eye, target, far, light, floor, floor_color, background=None, ambient=None):
    """A level's opening: its comment, effects, image, camera, light, and floor (a grid)."""
    text = comment + f'effects = ["{effects}"]\n'
    if ambient is not None:
        text += f"ambient = {number(ambient)}\n"
    text += f"\n[image]\nwidth = {size[0]}\nheight = {size[1]}\n"
    if background is not None:
        text += f"background = {vector(background)}\n"
    text += f"\n[camera]\neye = {vector(eye)}\ntarget = {vector(target)}\nfov_y = 70\nnear = 0.05\nfar = {far}\n"
    text += f"\n[[lights]]\ndirection = {vector(light)}\n"
    return text + f'\n[[objects]]\nname = "floor"\nshape = "grid"\nsize = {vector(floor)}\ncolor = {vector(floor_color)}\n\n'


def replace_cells(file, comment, parts):
    """Rewrites what follows the MARKER line of a level written by hand (or appends it):
    the comment, then its cells and portals."""
    path = STUDY / file
    text = path.read_text()
    text = text[: text.index(MARKER)] if MARKER in text else text.rstrip("\n") + "\n\n"
    path.write_text(text + MARKER + " (written by scripts/make_levels.py): " + comment + "".join(parts), newline="\n")


def cell(name, lo, hi):
    return f'\n[[cells]]\nname = "{name}"\nfrom = {vector(lo)}\nto = {vector(hi)}\n'


def portal(a, b, lo, hi):
    return f'\n[[portals]]\ncells = ["{a}", "{b}"]\nfrom = {vector(lo)}\nto = {vector(hi)}\n'


# ---------------------------------------------------------------------------------
# indoor: a hall along x, six rooms on each side, doors everywhere

# The walls reach 0.1 into the ceiling slab (from HEIGHT up), so that their tops and the
# ceiling's underside are not two faces at one depth.
HEIGHT, WALL_TOP, THICK, DOOR_W, DOOR_H = 3.0, 3.1, 0.2, 1.2, 2.2
ROOM_W, HALL_HALF, ROOM_DEPTH = 10.0, 2.0, 8.0
ROOMS = 6
X0 = -ROOM_W * ROOMS / 2  # -30
WALL = [0.78, 0.75, 0.68]
PARTITION = [0.7, 0.72, 0.76]


def wall_with_door(name, axis, at, lo, hi, door_center):
    """A wall on the plane `axis` = at, from lo to hi along the other horizontal axis, with a
    door DOOR_W wide and DOOR_H high centred at door_center: two pieces and a lintel."""
    pieces = []
    d0, d1 = door_center - DOOR_W / 2, door_center + DOOR_W / 2
    for part, (a, b, y0) in (("left", (lo, d0, 0.0)), ("right", (d1, hi, 0.0)), ("lintel", (d0, d1, DOOR_H))):
        if axis == "z":
            pieces.append(box(f"{name} {part}", [a, y0, at - THICK / 2], [b, WALL_TOP, at + THICK / 2], WALL if "hall" in name else PARTITION))
        else:
            pieces.append(box(f"{name} {part}", [at - THICK / 2, y0, a], [at + THICK / 2, WALL_TOP, b], PARTITION))
    return pieces


def indoor():
    out = [header("""# The indoor study's level (hsr study indoor; written by scripts/make_levels.py): a hall
# 60 long and 4 wide with six rooms on each side, 10 by 8, each room with a door to the
# hall and a door to each neighbour, all on one line, so that a walk down a row of rooms
# looks through five doors in a row. Furnished: a table, chairs, a shelf, crates; a
# ceiling. Divided into 18 cells (six stretches of hall, twelve rooms) and 27 portals.
""", "lambert", (960, 540), [-28, 1.6, 0], [0, 1.6, 0], 200, [-0.5, -0.6, -0.35], [60.2, 20.2],
                  [0.45, 0.4, 0.36], background=[0.1, 0.1, 0.12], ambient=0.35)]
    half_z = HALL_HALF + ROOM_DEPTH  # 10
    out.append(box("ceiling", [X0 - THICK / 2, HEIGHT, -half_z - THICK / 2], [-X0 + THICK / 2, HEIGHT + 0.2, half_z + THICK / 2], [0.85, 0.85, 0.82]) + "\n")
    for side, sign in (("north", 1), ("south", -1)):
        out.append(box(f"{side} outer wall", [X0 - THICK / 2, 0, sign * half_z - THICK / 2], [-X0 + THICK / 2, WALL_TOP, sign * half_z + THICK / 2], WALL) + "\n")
    for end, sign in (("west", -1), ("east", 1)):
        out.append(box(f"{end} end wall", [sign * -X0 - THICK / 2, 0, -half_z], [sign * -X0 + THICK / 2, WALL_TOP, half_z], WALL) + "\n")
    room_mid = HALL_HALF + ROOM_DEPTH / 2  # 6: the rooms' doors to each other
    for side, sign in (("north", 1), ("south", -1)):
        for i in range(ROOMS):
            x0 = X0 + i * ROOM_W
            center = x0 + ROOM_W / 2
            out += [p + "\n" for p in wall_with_door(f"{side} hall wall {i}", "z", sign * HALL_HALF, x0, x0 + ROOM_W, center)]
            if i > 0:
                z_lo, z_hi = sorted((sign * HALL_HALF, sign * half_z))
                out += [p + "\n" for p in wall_with_door(f"{side} partition {i}", "x", x0, z_lo, z_hi, sign * room_mid)]
            # Furniture, placed off the line of doors so the enfilade stays open.
            zf = sign * (room_mid + 2.2)  # the far half of the room
            out.append(box(f"{side} room {i} table", [center - 1.8, 0, zf - 0.5], [center - 0.2, 0.75, zf + 0.5], [0.55, 0.35, 0.2]) + "\n")
            for c, dx in enumerate((-2.3, 0.3)):
                out.append(box(f"{side} room {i} chair {c}", [center + dx - 0.22, 0, zf - 0.22], [center + dx + 0.22, 0.9, zf + 0.22], [0.4, 0.25, 0.15]) + "\n")
            shelf_z = sign * (half_z - 0.3)
            out.append(box(f"{side} room {i} shelf", [x0 + 6.5, 0, min(shelf_z, shelf_z - sign * 0.4)], [x0 + 8.8, 2.0, max(shelf_z, shelf_z - sign * 0.4)], [0.45, 0.3, 0.2]) + "\n")
            z_near = sign * (HALL_HALF + 0.6)
            out.append(f"""[[objects]]
name = "{side} room {i} crates"
shape = "box"
size = 0.5
translate = [0, 0.25, 0]
color = [0.6, 0.45, 0.25]
[objects.copies]
kind = "area"
count = 5
from = {vector([x0 + 0.8, 0, min(z_near, z_near + sign * 1.2)])}
to = {vector([x0 + 3.5, 0, max(z_near, z_near + sign * 1.2)])}
min_scale = [0.6, 1, 0.6]
max_scale = [1.2, 1, 1.2]
seed = {11 + i + (0 if sign > 0 else 50)}

""")
    out.append("""[[objects]]
name = "hall column"
shape = "cylinder"
radius = 0.15
height = 3.1
translate = [0, 1.55, 0]
color = [0.6, 0.6, 0.62]
[objects.copies]
kind = "grid"
count = [5, 1, 2]
spacing = [10, 0, 3.2]

""")
    out.append(MARKER + ": six stretches of hall, twelve rooms; each door a portal, and the hall's stretches\n"
               "# open into one another through their whole cross-section.\n")
    for i in range(ROOMS):
        x0 = X0 + i * ROOM_W
        out.append(cell(f"hall {i}", [x0, 0, -HALL_HALF], [x0 + ROOM_W, HEIGHT, HALL_HALF]))
        out.append(cell(f"north room {i}", [x0, 0, HALL_HALF], [x0 + ROOM_W, HEIGHT, half_z]))
        out.append(cell(f"south room {i}", [x0, 0, -half_z], [x0 + ROOM_W, HEIGHT, -HALL_HALF]))
    for i in range(ROOMS):
        x0 = X0 + i * ROOM_W
        center = x0 + ROOM_W / 2
        d0, d1 = center - DOOR_W / 2, center + DOOR_W / 2
        out.append(portal(f"hall {i}", f"north room {i}", [d0, 0, HALL_HALF], [d1, DOOR_H, HALL_HALF]))
        out.append(portal(f"hall {i}", f"south room {i}", [d0, 0, -HALL_HALF], [d1, DOOR_H, -HALL_HALF]))
        if i > 0:
            out.append(portal(f"hall {i - 1}", f"hall {i}", [x0, 0, -HALL_HALF], [x0, HEIGHT, HALL_HALF]))
            for side, sign in (("north", 1), ("south", -1)):
                zc = sign * room_mid
                out.append(portal(f"{side} room {i - 1}", f"{side} room {i}", [x0, 0, zc - DOOR_W / 2], [x0, DOOR_H, zc + DOOR_W / 2]))
    (STUDY / "indoor.toml").write_text("".join(out), newline="\n")


# ---------------------------------------------------------------------------------
# corridors: ten strips between the long walls (z = -40 + 8j); the cross walls, 5 long,
# stand across every long wall but the first (at x = -36 + 9i), so each strip is cut at
# each x_i by two stubs with a gap of 3 between them (the first strip: one stub, a gap
# of 5.5). The strips' ends (beyond x = +-40) open into one another and into a margin
# beyond the outermost walls.

def corridors():
    comment = ("each strip between two long walls cut\n"
               "# into ten cells at the cross walls' centre lines, a portal at each gap between the\n"
               "# cross walls' stubs; where the long walls end (|x| > 40) the strips open into one\n"
               "# another and into a margin beyond the outermost walls. The walls are as tall as the\n"
               "# cells (3), and nothing stands higher: a line of sight over a wall climbs into nothing.\n")
    out = []
    xs = [-45] + [-36 + 9 * i for i in range(9)] + [45]
    strips = [(-40 + 8 * j, -32 + 8 * j) for j in range(10)]
    out.append(cell("south margin", [-45, 0, -45], [45, 3, -40]))
    out.append(cell("north margin", [-45, 0, 40], [45, 3, 45]))
    for j, (z0, z1) in enumerate(strips):
        for i in range(10):
            out.append(cell(f"strip {j} part {i}", [xs[i], 0, z0], [xs[i + 1], 3, z1]))
    for j, (z0, z1) in enumerate(strips):
        for i in range(1, 10):
            # The stubs reach 2.5 into the strip from each long wall they cross.
            gap_from = z0 + 2.5 if j > 0 else z0
            out.append(portal(f"strip {j} part {i - 1}", f"strip {j} part {i}", [xs[i], 0, gap_from], [xs[i], 3, z1 - 2.5]))
        # The ends, past the long walls: open to the next strip (or the margin).
        below = "south margin" if j == 0 else None
        for i, (x0, x1) in ((0, (-45, -40)), (9, (40, 45))):
            lower = below if below else f"strip {j - 1} part {i}"
            out.append(portal(lower, f"strip {j} part {i}", [x0, 0, z0], [x1, 3, z0]))
            if j == 9:
                out.append(portal(f"strip {j} part {i}", "north margin", [x0, 0, z1], [x1, 3, z1]))
    replace_cells("corridors.toml", comment, out)


# ---------------------------------------------------------------------------------
# portal_rooms: three by three rooms, 6 by 6, doors at different places in each wall, a
# pillar in each room; no ceiling (the walls are as tall as the cells).

def portal_rooms():
    size, n = 6.0, 3
    lo = -size * n / 2  # -9
    out = [header("""# Nine rooms, three by three, 6 by 6 and 3 high, each wall between two rooms with one
# door (written by scripts/make_levels.py): the doors sit at different places along
# their walls, so what a chain of doors shows narrows quickly and differs between rect
# and polygon narrowing. A pillar stands in each room. The portal tests
# (tests/culling/cells_test.cpp) walk lines of sight through it cell by cell and compare
# the cells they reach with the portal traversal's, from eyes all over the middle room.
""", "flat", (320, 240), [1.5, 1.6, 2.2], [-3, 1.2, -6], 100, [-0.4, -1, -0.3], [18.2, 18.2],
                  [0.5, 0.46, 0.4], background=[0.2, 0.22, 0.28])]
    hi = -lo
    for name, lo3, hi3 in (("west wall", [lo - THICK / 2, 0, lo], [lo + THICK / 2, HEIGHT, hi]),
                           ("east wall", [hi - THICK / 2, 0, lo], [hi + THICK / 2, HEIGHT, hi]),
                           ("south wall", [lo, 0, lo - THICK / 2], [hi, HEIGHT, lo + THICK / 2]),
                           ("north wall", [lo, 0, hi - THICK / 2], [hi, HEIGHT, hi + THICK / 2])):
        out.append(box(name, lo3, hi3, WALL) + "\n")
    # Door offsets from each wall segment's middle: varied, deterministic.
    offsets = [-1.8, 0.9, -0.4, 1.7, -1.2, 0.3, 1.4, -0.9, 0.0, -1.5, 1.1, 0.6]
    portals, k = [], 0
    for i in range(n):
        for j in range(n):
            x0, z0 = lo + i * size, lo + j * size
            out.append(box(f"pillar {i} {j}", [x0 + 1.5 + (i + 2 * j) % 3, 0, z0 + 1.2 + (2 * i + j) % 4],
                           [x0 + 2.1 + (i + 2 * j) % 3, 2.0, z0 + 1.8 + (2 * i + j) % 4], [0.35 + 0.1 * i, 0.4, 0.3 + 0.15 * j]) + "\n")
            if i > 0:  # the wall at x = x0 between rooms (i - 1, j) and (i, j)
                center = z0 + size / 2 + offsets[k % len(offsets)]
                k += 1
                out += [p + "\n" for p in wall_with_door(f"wall x {i} {j}", "x", x0, z0, z0 + size, center)]
                portals.append(portal(f"room {i - 1} {j}", f"room {i} {j}", [x0, 0, center - DOOR_W / 2], [x0, DOOR_H, center + DOOR_W / 2]))
            if j > 0:  # the wall at z = z0 between rooms (i, j - 1) and (i, j)
                center = x0 + size / 2 + offsets[k % len(offsets)]
                k += 1
                out += [p + "\n" for p in wall_with_door(f"wall z {i} {j}", "z", z0, x0, x0 + size, center)]
                portals.append(portal(f"room {i} {j - 1}", f"room {i} {j}", [center - DOOR_W / 2, 0, z0], [center + DOOR_W / 2, DOOR_H, z0]))
    out.append(MARKER + ": a cell per room, a portal per door.\n")
    for i in range(n):
        for j in range(n):
            out.append(cell(f"room {i} {j}", [lo + i * size, 0, lo + j * size], [lo + (i + 1) * size, HEIGHT, lo + (j + 1) * size]))
    out += portals
    (STUDY.parent / "hard" / "portal_rooms.toml").write_text("".join(out), newline="\n")


# ---------------------------------------------------------------------------------
# portal_row: three rooms in a row, the doors between them on one line, a crate in the
# middle of each room: a level where everything the portal chains admit can be seen from
# somewhere, so the two PVS builds must agree.

def portal_row():
    size, n = 4.0, 3
    out = [header("""# Three rooms in a row, 4 by 4 and 3 high, joined by doors on one line, a crate in the
# middle of each (written by scripts/make_levels.py). Everything a chain of doors admits
# is seen from somewhere in each room: the sampled visible sets, with enough samples,
# equal the conservative ones (tests/culling/cells_test.cpp).
""", "flat", (320, 240), [-5, 1.6, 0.5], [6, 1.2, 0], 100, [-0.4, -1, -0.3], [12.2, 4.2],
                  [0.5, 0.46, 0.4])]
    lo, hi = -size * n / 2, size * n / 2
    for name, lo3, hi3 in (("south wall", [lo - THICK / 2, 0, -2 - THICK / 2], [hi + THICK / 2, HEIGHT, -2 + THICK / 2]),
                           ("north wall", [lo - THICK / 2, 0, 2 - THICK / 2], [hi + THICK / 2, HEIGHT, 2 + THICK / 2]),
                           ("west wall", [lo - THICK / 2, 0, -2], [lo + THICK / 2, HEIGHT, 2]),
                           ("east wall", [hi - THICK / 2, 0, -2], [hi + THICK / 2, HEIGHT, 2])):
        out.append(box(name, lo3, hi3, WALL) + "\n")
    cells, portals = [], []
    for i in range(n):
        x0 = lo + i * size
        out.append(box(f"crate {i}", [x0 + size / 2 - 0.3, 0, -0.3], [x0 + size / 2 + 0.3, 0.6, 0.3], [0.6, 0.45, 0.25]) + "\n")
        cells.append(cell(f"room {i}", [x0, 0, -2], [x0 + size, HEIGHT, 2]))
        if i > 0:
            out += [p + "\n" for p in wall_with_door(f"wall {i}", "x", x0, -2, 2, 0)]
            portals.append(portal(f"room {i - 1}", f"room {i}", [x0, 0, -DOOR_W / 2], [x0, DOOR_H, DOOR_W / 2]))
    out.append(MARKER + ": a cell per room, a portal per door.\n")
    (STUDY.parent / "hard" / "portal_row.toml").write_text("".join(out + cells + portals), newline="\n")


# ---------------------------------------------------------------------------------
# castle: three courtyards inside closed curtain walls (10 high), parted by inner walls
# (7 high) with a gap at each end; the ground outside; and the sky above the walls,
# where the towers and the keep rise.

def castle():
    comment = ("the three courtyards up to the inner\n"
               "# walls' height (7), one cell over all three up to the curtain walls' (10), the\n"
               "# ground outside in four boxes, and the sky above (to 60). The courtyards open into\n"
               "# one another through the gaps at the inner walls' ends, and upward; everything opens\n"
               "# into the sky. The curtain walls and their corner towers close the castle.\n")
    out = []
    yards = [("west courtyard", -30, -10), ("middle courtyard", -10, 10), ("east courtyard", 10, 30)]
    for name, x0, x1 in yards:
        out.append(cell(name, [x0, 0, -30], [x1, 7, 30]))
    out.append(cell("over the inner walls", [-30, 7, -30], [30, 10, 30]))
    outside = [("outside south", [-100, 0, -100], [100, 10, -30]), ("outside north", [-100, 0, 30], [100, 10, 100]),
               ("outside west", [-100, 0, -30], [-30, 10, 30]), ("outside east", [30, 0, -30], [100, 10, 30])]
    for name, lo, hi in outside:
        out.append(cell(name, lo, hi))
    out.append(cell("sky", [-100, 10, -100], [100, 60, 100]))
    for name, x0, x1 in yards:
        out.append(portal(name, "over the inner walls", [x0, 7, -30], [x1, 7, 30]))
    for (a, _, x), (b, _, _) in zip(yards, yards[1:]):
        # The inner walls span z = -28 .. 28: a gap of 2 at each end.
        out.append(portal(a, b, [x, 0, 28], [x, 7, 30]))
        out.append(portal(a, b, [x, 0, -30], [x, 7, -28]))
    out.append(portal("over the inner walls", "sky", [-30, 10, -30], [30, 10, 30]))
    for name, lo, hi in outside:
        out.append(portal(name, "sky", [lo[0], 10, lo[2]], [hi[0], 10, hi[2]]))
    for z, side in ((-30, "outside south"), (30, "outside north")):
        out.append(portal(side, "outside west", [-100, 0, z], [-30, 10, z]))
        out.append(portal(side, "outside east", [30, 0, z], [100, 10, z]))
    replace_cells("castle.toml", comment, out)


if __name__ == "__main__":
    indoor()
    castle()
    portal_rooms()
    portal_row()
    corridors()
