#!/usr/bin/env python3
"""Writes the regression suite's tiny textures (pure Python, no image library), so that they are documented:

  checker.png   16x16 sRGB colour checker (diffuse texture, pbr base colour)
  mr.png        16x16 linear metallic-roughness map: G = roughness 0.75..1, B = metallic 0 or 1 (stripes)
  normal.png    16x16 tangent-space normal map of gentle bumps (tilt <= ~17 degrees)
  emissive.png  8x8 sRGB emission pattern (warm/cool halves with a brighter centre)
  sky.hdr       32x16 equirectangular sky (Radiance RGBE): blue gradient, a bright ~25-degree sun blob, dark ground

Run from anywhere; files go next to this script. The committed files are this script's output."""
import math, pathlib, struct, zlib

here = pathlib.Path(__file__).resolve().parent


def write_png(path, w, h, rgb):
    """rgb: list of rows of (r, g, b) bytes; 8-bit RGB, no interlace."""
    raw = b"".join(b"\x00" + bytes(c for px in row for c in px) for row in rgb)
    def chunk(tag, data):
        return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data) & 0xFFFFFFFF)
    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")
    path.write_bytes(png)


def rgbe(r, g, b):
    m = max(r, g, b)
    if m < 1e-32:
        return bytes([0, 0, 0, 0])
    e = math.frexp(m)[1]
    s = 256.0 / (2.0 ** e)
    return bytes([min(255, int(r * s)), min(255, int(g * s)), min(255, int(b * s)), e + 128])


def write_hdr(path, w, h, rows):
    """Flat (not run-length encoded) Radiance RGBE, top row first."""
    head = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n" + f"-Y {h} +X {w}\n".encode()
    path.write_bytes(head + b"".join(rgbe(*px) for row in rows for px in row))


def byte(x):
    return max(0, min(255, int(round(x * 255))))


def checker():
    a, b = (220, 200, 60), (40, 90, 170)
    return [[a if ((x // 4) + (y // 4)) % 2 == 0 else b for x in range(16)] for y in range(16)]


def metallic_roughness():
    rows = []
    for y in range(16):
        rough = 0.75 + 0.25 * y / 15
        rows.append([(0, byte(rough), 255 if (x // 4) % 2 else 0) for x in range(16)])
    return rows


def normal_map():
    rows = []
    for y in range(16):
        row = []
        for x in range(16):
            u, v = (x + 0.5) / 16, (y + 0.5) / 16
            nx = 0.3 * math.cos(2 * math.pi * 2 * u) * math.sin(2 * math.pi * v)
            ny = 0.3 * math.sin(2 * math.pi * 2 * u) * math.cos(2 * math.pi * v)
            nz = math.sqrt(max(0.0, 1 - nx * nx - ny * ny))
            row.append(tuple(byte(0.5 * c + 0.5) for c in (nx, ny, nz)))
        rows.append(row)
    return rows


def emissive():
    rows = []
    for y in range(8):
        row = []
        for x in range(8):
            base = (1.0, 0.55, 0.25) if x < 4 else (0.35, 0.6, 1.0)
            k = 1.0 if 2 <= x <= 5 and 2 <= y <= 5 else 0.55
            row.append(tuple(byte(k * c) for c in base))
        rows.append(row)
    return rows


def sky():
    w, h = 32, 16
    sun = (math.radians(40), math.radians(50))  # (elevation, azimuth)
    sd = (math.cos(sun[0]) * math.cos(sun[1]), math.sin(sun[0]), math.cos(sun[0]) * math.sin(sun[1]))
    rows = []
    for y in range(h):
        theta = math.pi * (y + 0.5) / h  # from +Y
        row = []
        for x in range(w):
            phi = 2 * math.pi * (x + 0.5) / w
            d = (math.sin(theta) * math.cos(phi), math.cos(theta), math.sin(theta) * math.sin(phi))
            if d[1] >= 0:
                t = d[1]
                c = [0.9 - 0.5 * t, 1.0 - 0.3 * t, 1.3]
            else:
                c = [0.15, 0.13, 0.1]
            cosang = sum(a * b for a, b in zip(d, sd))
            if cosang > math.cos(math.radians(25)):
                c = [v + k for v, k in zip(c, (12.0, 10.0, 7.0))]
            row.append(tuple(c))
        rows.append(row)
    return w, h, rows


write_png(here / "checker.png", 16, 16, checker())
write_png(here / "mr.png", 16, 16, metallic_roughness())
write_png(here / "normal.png", 16, 16, normal_map())
write_png(here / "emissive.png", 8, 8, emissive())
write_hdr(here / "sky.hdr", *sky())
print("wrote checker.png mr.png normal.png emissive.png sky.hdr in", here)
