"""Writes the images of the normal-, bump- and opacity-map test scene into
crates/pathtrace-scene/tests/data/maps/ (plain Python, no dependencies):

- normal.png: a tangent-space normal map (8-bit RGB, to be read raw) of a field of round bumps,
  n ∝ (−∂h/∂x, −∂h/∂y, 1) with h = ½·sin(2πx·3)·sin(2πy·3) stretched by 0.4, encoded (n + 1)/2,
  +y pointing to the top of the image (decreasing v);
- height.png: an 8-bit grey height field of diagonal ridges, h = ½ + ½·sin(2π·(x + 2y)·2);
- mask.png: an 8-bit grey opacity mask, a disc of 1 with a square hole of 0 and 0 outside;
- cutout.png: the same mask as the alpha channel of an 8-bit RGBA image of one colour
  (sRGB 200, 120, 60), for glTF's alphaMode.

    python3 benches/peers/make_map_assets.py
"""
import math
import os
import struct
import zlib

OUT = os.path.join(os.path.dirname(__file__), "../../crates/pathtrace-scene/tests/data/maps")
SIZE = 32


def write_png(path, rows, channels):
    """rows: SIZE lists of SIZE*channels bytes (0..255), first row at the top."""
    colour = {1: 0, 3: 2, 4: 6}[channels]
    raw = b"".join(b"\0" + bytes(r) for r in rows)

    def chunk(tag, data):
        return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data) & 0xFFFFFFFF)

    header = struct.pack(">IIBBBBB", SIZE, SIZE, 8, colour, 0, 0, 0)
    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")
    with open(path, "wb") as f:
        f.write(png)


def byte(x):
    return max(0, min(255, int(round(x * 255))))


def main():
    os.makedirs(OUT, exist_ok=True)
    normal, height, mask, cutout = [], [], [], []
    for j in range(SIZE):
        y = (j + 0.5) / SIZE  # v: down the image
        nrow, hrow, mrow, crow = [], [], [], []
        for i in range(SIZE):
            x = (i + 0.5) / SIZE
            k = 2 * math.pi * 3
            dx = 0.4 * 0.5 * k * math.cos(k * x) * math.sin(k * y)
            dv = 0.4 * 0.5 * k * math.sin(k * x) * math.cos(k * y)
            # Tangent space: +x along u, +y along −v (the image's up).
            n = (-dx, dv, 1.0)
            length = math.sqrt(sum(c * c for c in n))
            nrow += [byte((c / length + 1) / 2) for c in n]
            hrow.append(byte(0.5 + 0.5 * math.sin(2 * math.pi * (x + 2 * y) * 2)))
            r = math.hypot(x - 0.5, y - 0.5)
            hole = abs(x - 0.5) < 0.15 and abs(y - 0.5) < 0.15
            mrow.append(255 if r < 0.48 and not hole else 0)
            crow += [200, 120, 60, mrow[-1]]
        normal.append(nrow)
        height.append(hrow)
        mask.append(mrow)
        cutout.append(crow)
    write_png(os.path.join(OUT, "normal.png"), normal, 3)
    write_png(os.path.join(OUT, "height.png"), height, 1)
    write_png(os.path.join(OUT, "mask.png"), mask, 1)
    write_png(os.path.join(OUT, "cutout.png"), cutout, 4)


if __name__ == "__main__":
    main()
