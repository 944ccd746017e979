#!/usr/bin/env python3
"""A z-buffer written apart from hsr, in plain Python: one of the correct variants
hsr grade --self-check must pass. It keeps each pixel's view distance as a double
(hsr's z-buffer stores float32 z): where the two disagree, only the reference decides.

    python3 zbuffer.py SCENE.tri IDS.png DEPTH.pfm [--order submission|reverse]

DEPTH.pfm: each pixel's view distance, the depth image Exercise 1 asks for.

reverse: the triangles drawn last to first, a tie then given to the lower id, so that
the image is the one submission order gives: the same answer by another traversal.

It reads the triangle file (renderer/scene/triangle_file.hpp) through its clip_from_world
matrix alone, clips each triangle to near <= d <= far, samples pixel centers with the
top-left rule, and keeps the nearest distance with a strict test (ties: the first drawn).
"""
import struct
import sys
import zlib


def read_scene(path):
    words = []
    with open(path) as f:
        lines = [line.split('#')[0].split() for line in f]
    lines = [line for line in lines if line]
    assert lines[0] == ['hsr-triangles', '1'], 'not a triangle file'
    scene = {'triangles': []}
    k = 1
    while k < len(lines):
        key = lines[k][0]
        if key == 'clip_from_world':
            scene['matrix'] = [[float(v) for v in lines[k + r]] for r in range(1, 5)]
            k += 5
            continue
        if key == 'triangles':
            count = int(lines[k][1])
            for t in range(count):
                v = [float(x) for x in lines[k + 1 + t]]
                scene['triangles'].append((v[0:3], v[3:6], v[6:9]))
            break
        scene[key] = lines[k][1:]
        k += 1
    return scene


def clip(polygon, inside, cross):
    """Sutherland-Hodgman against one plane: keep the vertices inside, add crossings."""
    result = []
    for i, a in enumerate(polygon):
        b = polygon[(i + 1) % len(polygon)]
        if inside(a):
            result.append(a)
        if inside(a) != inside(b):
            result.append(cross(a, b))
    return result


def lerp(a, b, s):
    return tuple(x + (y - x) * s for x, y in zip(a, b))


def render(scene, reverse):
    width, height = int(scene['size'][0]), int(scene['size'][1])
    near, far = float(scene['near'][0]), float(scene['far'][0])
    perspective = scene['projection'][0] == 'perspective'
    m = scene['matrix']
    ids = [0] * (width * height)
    depth = [float('inf')] * (width * height)
    numbered = list(enumerate(scene['triangles'], start=1))
    for number, corners in reversed(numbered) if reverse else numbered:
        # Clip space: (x, y, d, w), each linear in the position.
        polygon = [tuple(sum(m[r][c] * p[c] for c in range(3)) + m[r][3] for r in range(4)) for p in corners]
        polygon = clip(polygon, lambda v: v[2] >= near, lambda a, b: lerp(a, b, (near - a[2]) / (b[2] - a[2])))
        polygon = clip(polygon, lambda v: v[2] <= far, lambda a, b: lerp(a, b, (far - a[2]) / (b[2] - a[2])))
        if len(polygon) < 3:
            continue
        screen = [((x / w * 0.5 + 0.5) * width, (0.5 - y / w * 0.5) * height, d) for x, y, d, w in polygon]
        for k in range(1, len(screen) - 1):
            draw(screen[0], screen[k], screen[k + 1], number, perspective, width, height, ids, depth, reverse)
    return width, height, ids, depth


def draw(a, b, c, number, perspective, width, height, ids, depth, reverse):
    area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
    if area == 0:
        return
    if area < 0:  # either winding: make it clockwise on screen (y down)
        b, c, area = c, b, -area
    v = (a, b, c)
    edges = []
    for k in range(3):
        p, q = v[(k + 1) % 3], v[(k + 2) % 3]
        dx, dy = q[0] - p[0], q[1] - p[1]
        top_left = (dy == 0 and dx > 0) or dy < 0
        edges.append((p, dx, dy, top_left))
    xs, ys = [p[0] for p in v], [p[1] for p in v]
    x0, x1 = max(0, int(-(-(min(xs) - 0.5) // 1))), min(width - 1, int((max(xs) - 0.5) // 1))
    y0, y1 = max(0, int(-(-(min(ys) - 0.5) // 1))), min(height - 1, int((max(ys) - 0.5) // 1))
    for py in range(y0, y1 + 1):
        cy = py + 0.5
        for px in range(x0, x1 + 1):
            cx = px + 0.5
            weights = []
            for p, dx, dy, top_left in edges:
                e = dx * (cy - p[1]) - dy * (cx - p[0])
                if e < 0 or (e == 0 and not top_left):
                    break
                weights.append(e / area)
            else:
                if perspective:  # 1/d is affine on the screen
                    d = 1 / sum(wk / vk[2] for wk, vk in zip(weights, v))
                else:
                    d = sum(wk * vk[2] for wk, vk in zip(weights, v))
                pixel = py * width + px
                if d < depth[pixel] or (reverse and d == depth[pixel] and number < ids[pixel]):
                    depth[pixel] = d
                    ids[pixel] = number


def write_png(path, width, height, ids):
    rows = b''.join(b'\0' + b''.join(struct.pack('>I', i)[1:] for i in ids[y * width:(y + 1) * width]) for y in range(height))

    def chunk(kind, data):
        return struct.pack('>I', len(data)) + kind + data + struct.pack('>I', zlib.crc32(kind + data) & 0xFFFFFFFF)

    with open(path, 'wb') as f:
        f.write(b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', width, height, 8, 2, 0, 0, 0)) +
                chunk(b'IDAT', zlib.compress(rows)) + chunk(b'IEND', b''))


def write_pfm(path, width, height, depth):
    # A portable float map: a header, then float32s, little-endian, rows from the bottom up.
    rows = b''.join(struct.pack('<%df' % width, *depth[y * width:(y + 1) * width]) for y in reversed(range(height)))
    with open(path, 'wb') as f:
        f.write(b'Pf\n%d %d\n-1.0\n' % (width, height) + rows)


if __name__ == '__main__':
    reverse = sys.argv[4:] == ['--order', 'reverse']
    width, height, ids, depth = render(read_scene(sys.argv[1]), reverse)
    write_png(sys.argv[2], width, height, ids)
    write_pfm(sys.argv[3], width, height, depth)
