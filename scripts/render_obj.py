#!/usr/bin/env python3
"""Renders an OBJ triangle mesh (as written by `freeform surface --obj` or
`freeform mesh`) to a PNG with a z-buffer and two-sided smooth-ish shading,
using only the Python standard library, so a mesh can be looked at on a
machine without a viewer.

    scripts/render_obj.py teapot.obj teapot.png [--size 400]
        [--azimuth 30] [--elevation 20]
"""
import argparse
import math
import struct
import zlib


def read_obj(path):
    vertices, normals, faces = [], [], []
    with open(path) as obj:
        for line in obj:
            fields = line.split()
            if not fields:
                continue
            if fields[0] == "v":
                vertices.append(tuple(map(float, fields[1:4])))
            elif fields[0] == "vn":
                normals.append(tuple(map(float, fields[1:4])))
            elif fields[0] == "f":
                faces.append([int(c.split("/")[0]) - 1 for c in fields[1:4]])
    return vertices, normals, faces


def view_transform(azimuth, elevation):
    a, b = math.radians(azimuth), math.radians(elevation)

    def rotate(p):
        x, y, z = p
        x, y = x * math.cos(a) - y * math.sin(a), x * math.sin(a) + y * math.cos(a)
        y, z = y * math.cos(b) - z * math.sin(b), y * math.sin(b) + z * math.cos(b)
        return x, y, z  # y is depth (larger is farther)

    return rotate


def render(vertices, normals, faces, size, rotate):
    projected = [rotate(v) for v in vertices]
    xs = [p[0] for p in projected]
    zs = [p[2] for p in projected]
    scale = 0.9 * min(size / (max(xs) - min(xs) or 1), size / (max(zs) - min(zs) or 1))
    cx, cz = (max(xs) + min(xs)) / 2, (max(zs) + min(zs)) / 2
    screen = [(size / 2 + (p[0] - cx) * scale, size / 2 - (p[2] - cz) * scale, p[1])
              for p in projected]
    depth = [[math.inf] * size for _ in range(size)]
    image = [[(255, 255, 255)] * size for _ in range(size)]
    light = (0.3, -0.8, 0.5)
    norm = math.sqrt(sum(c * c for c in light))
    light = [c / norm for c in light]
    for face in faces:
        a, b, c = (screen[i] for i in face)
        if normals:
            n = rotate(tuple(sum(normals[i][k] for i in face) for k in range(3)))
        else:
            pa, pb, pc = (projected[i] for i in face)
            u = [pb[k] - pa[k] for k in range(3)]
            v = [pc[k] - pa[k] for k in range(3)]
            n = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                 u[0] * v[1] - u[1] * v[0])
        length = math.sqrt(sum(k * k for k in n)) or 1.0
        shade = max(0.1, abs(sum(n[k] * light[k] for k in range(3))) / length)
        color = (int(60 + 180 * shade), int(80 + 150 * shade), int(40 + 200 * shade))
        det = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])
        if abs(det) < 1e-12:
            continue
        for y in range(max(0, int(min(a[1], b[1], c[1]))),
                       min(size - 1, int(max(a[1], b[1], c[1])) + 1) + 1):
            for x in range(max(0, int(min(a[0], b[0], c[0]))),
                           min(size - 1, int(max(a[0], b[0], c[0])) + 1) + 1):
                w1 = ((x - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (y - a[1])) / det
                w2 = ((b[0] - a[0]) * (y - a[1]) - (x - a[0]) * (b[1] - a[1])) / det
                w0 = 1 - w1 - w2
                if min(w0, w1, w2) < 0:
                    continue
                z = w0 * a[2] + w1 * b[2] + w2 * c[2]
                if z < depth[y][x]:
                    depth[y][x] = z
                    image[y][x] = color
    return image


def write_png(path, image):
    height, width = len(image), len(image[0])
    raw = b"".join(b"\x00" + bytes(c for pixel in row for c in pixel) for row in image)

    def chunk(kind, data):
        return (struct.pack(">I", len(data)) + kind + data +
                struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF))

    with open(path, "wb") as png:
        png.write(b"\x89PNG\r\n\x1a\n" +
                  chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
                  chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("obj")
    parser.add_argument("png")
    parser.add_argument("--size", type=int, default=400)
    parser.add_argument("--azimuth", type=float, default=30)
    parser.add_argument("--elevation", type=float, default=20)
    args = parser.parse_args()
    vertices, normals, faces = read_obj(args.obj)
    image = render(vertices, normals, faces, args.size,
                   view_transform(args.azimuth, args.elevation))
    write_png(args.png, image)


if __name__ == "__main__":
    main()
