"""Reads the PNGs the figure commands write (8-bit greyscale, RGB or RGBA,
not interlaced: what gnuplot's pngcairo terminal and libpng write here) into
rows of pixels, and measures what a person would see: the size, how much of
it is not background, and how many framed panels are stacked in it."""
import struct
import zlib


def read(path):
    """Returns (width, height, rows); rows[y][x] is a tuple of channels."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError(path + ": not a PNG")
    pos, idat, ihdr = 8, b"", None
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            ihdr = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    w, h, depth, colour, _, _, interlace = ihdr
    channels = {0: 1, 2: 3, 4: 2, 6: 4}.get(colour)
    if depth != 8 or channels is None or interlace:
        raise ValueError("%s: unsupported PNG (depth %d, colour type %d, interlace %d)" % (path, depth, colour, interlace))
    raw = zlib.decompress(idat)
    stride = w * channels
    rows, prev = [], bytearray(stride)
    for y in range(h):
        ftype = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - channels] if i >= channels else 0
            b = prev[i]
            c = prev[i - channels] if i >= channels else 0
            if ftype == 1:
                line[i] = (line[i] + a) & 255
            elif ftype == 2:
                line[i] = (line[i] + b) & 255
            elif ftype == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif ftype == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append([tuple(line[x * channels:(x + 1) * channels]) for x in range(w)])
        prev = line
    return w, h, rows


def ink_fraction(rows):
    """Fraction of pixels that differ from the top-left (background) pixel."""
    bg = rows[0][0]
    total = sum(len(r) for r in rows)
    return sum(1 for r in rows for p in r if p != bg) / total


def dark(p):
    return max(p[:3]) < 80


def horizontal_lines(rows, min_fraction=0.4):
    """Rows holding a dark horizontal line over at least min_fraction of the
    width (the frames of plot panels), merged when adjacent: their y."""
    w = len(rows[0])
    ys = []
    for y, r in enumerate(rows):
        run = best = 0
        for p in r:
            run = run + 1 if dark(p) else 0
            best = max(best, run)
        if best >= min_fraction * w:
            ys.append(y)
    lines = []
    for y in ys:
        if lines and y - lines[-1][-1] <= 1:
            lines[-1].append(y)
        else:
            lines.append([y])
    return [l[0] for l in lines]


def panel_count(rows):
    """Framed plot panels stacked vertically: each has a top and a bottom frame line."""
    return len(horizontal_lines(rows)) // 2
