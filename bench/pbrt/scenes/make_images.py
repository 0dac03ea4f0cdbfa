#!/usr/bin/env python3
"""Writes the images the pbrt-v4 feature scenes use (bench/pbrt/scenes/textures/), so that they
are reproducible: a 64 x 64 sRGB PNG of coloured tiles (textures.pbrt) and a 64 x 64 equal-area
EXR sky with a bright, small sun (environment.pbrt). Standard library only: PNG through zlib,
EXR written uncompressed (scanlines of 32-bit floats). Usage: make_images.py [DIR]"""
import math
import os
import struct
import sys
import zlib


def png(path, w, h, pixel):
    rows = b"".join(b"\x00" + bytes(c for x in range(w) for c in pixel(x, y)) for y in range(h))
    chunk = lambda t, d: struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xFFFFFFFF)
    data = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
    data += chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b"")
    open(path, "wb").write(data)


def exr(path, w, h, pixel):
    """Uncompressed scanline OpenEXR, channels B, G, R (alphabetical) as 32-bit floats."""
    def attr(name, typ, value):
        return name.encode() + b"\0" + typ.encode() + b"\0" + struct.pack("<i", len(value)) + value
    chans = b"".join(c.encode() + b"\0" + struct.pack("<iBBBBii", 2, 0, 0, 0, 0, 1, 1) for c in "BGR") + b"\0"
    box = struct.pack("<iiii", 0, 0, w - 1, h - 1)
    header = (attr("channels", "chlist", chans) + attr("compression", "compression", b"\0") +
              attr("dataWindow", "box2i", box) + attr("displayWindow", "box2i", box) +
              attr("lineOrder", "lineOrder", b"\0") + attr("pixelAspectRatio", "float", struct.pack("<f", 1.0)) +
              attr("screenWindowCenter", "v2f", struct.pack("<ff", 0.0, 0.0)) +
              attr("screenWindowWidth", "float", struct.pack("<f", 1.0)) + b"\0")
    head = struct.pack("<ii", 20000630, 2) + header
    line_size = w * 3 * 4
    offsets_at = len(head) + 8 * h
    out = bytearray(head)
    out += b"".join(struct.pack("<Q", offsets_at + y * (8 + line_size)) for y in range(h))
    for y in range(h):
        px = [pixel(x, y) for x in range(w)]
        out += struct.pack("<ii", y, line_size)
        for c in (2, 1, 0):  # B, G, R
            out += struct.pack("<%df" % w, *[p[c] for p in px])
    open(path, "wb").write(bytes(out))


def tiles(x, y):
    """8 x 8 tiles of eight colours, a darker grout line between them."""
    if x % 8 == 0 or y % 8 == 0:
        return (40, 40, 40)
    palette = [(230, 80, 60), (60, 170, 90), (70, 110, 220), (235, 210, 80),
               (200, 200, 200), (150, 60, 170), (40, 190, 200), (240, 140, 40)]
    return palette[(x // 8 + 3 * (y // 8)) % 8]


def equal_area_direction(u, v):
    """pbrt-v4's EqualAreaSquareToSphere, written from Clarberg (2008): (u, v) in [0, 1]^2."""
    u, v = 2 * u - 1, 2 * v - 1
    up, vp = abs(u), abs(v)
    sd = 1 - (up + vp)
    d = abs(sd)
    r = 1 - d
    phi = (1 if r == 0 else (vp - up) / r + 1) * math.pi / 4
    z = math.copysign(1 - r * r, sd)
    k = r * math.sqrt(max(0.0, 2 - r * r))
    return (math.copysign(math.cos(phi), u) * k, math.copysign(math.sin(phi), v) * k, z)


def sky(x, y, n=64):
    """A blue sky brighter toward the horizon, a dim brown ground, and a small sun of about
    0.02 sr toward (0.5, 0.3, 0.8) (pbrt-v4's +z up in the light's frame)."""
    d = equal_area_direction((x + 0.5) / n, (y + 0.5) / n)
    if d[2] < 0:
        return (0.08, 0.06, 0.04)
    t = 1 - d[2]
    col = (0.25 + 0.45 * t, 0.4 + 0.4 * t, 0.9 + 0.1 * t)
    s = (0.5, 0.3, 0.8)
    norm = math.sqrt(sum(c * c for c in s))
    if sum(a * b / norm for a, b in zip(d, s)) > math.cos(math.radians(5.0)):
        return (60.0, 55.0, 45.0)
    return col


if __name__ == "__main__":
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "textures")
    os.makedirs(out, exist_ok=True)
    png(os.path.join(out, "tiles.png"), 64, 64, tiles)
    exr(os.path.join(out, "sky-equal-area.exr"), 64, 64, sky)
