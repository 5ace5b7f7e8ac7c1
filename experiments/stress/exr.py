"""The main R, G, B channels of the EXRs `bundlelab render` writes (scanline, FLOAT channels, no or
ZIP compression: core/image/ImageIO.cpp), with the standard library only. The same format as
experiments/atlas-discretization.py reads with numpy; the stress suite runs on /usr/bin/python3
without numpy, so this reads it with zlib and array."""
import array
import itertools
import struct
import sys
import zlib

_LINES = {0: 1, 2: 1, 3: 16}  # compression -> scanlines per chunk: none, ZIPS, ZIP
_SIZE = {0: 4, 1: 2, 2: 4}  # pixel type -> bytes: uint, half, float (R, G, B must be float)


def _header(d):
    i, header = 8, {}
    while d[i] != 0:
        name = d[i:d.index(b"\0", i)]
        i += len(name) + 1
        kind = d[i:d.index(b"\0", i)]
        i += len(kind) + 1
        size = struct.unpack_from("<i", d, i)[0]
        i += 4
        header[name.decode()] = d[i:i + size]
        i += size
    return header, i + 1


def _channels(c):
    out, j = [], 0
    while c[j] != 0:
        name = c[j:c.index(b"\0", j)].decode()
        j += len(name) + 1
        out.append((name, struct.unpack_from("<i", c, j)[0]))
        j += 16
    return out


def _unzip(raw):
    """ZIP chunk: inflate, undo the byte-delta predictor, undo the two-halves interleave."""
    b = zlib.decompress(raw)
    t = bytes(itertools.accumulate(b, lambda prev, x: (prev + x - 128) & 0xFF))
    half = (len(t) + 1) // 2
    out = bytearray(len(t))
    out[0::2], out[1::2] = t[:half], t[half:]
    return bytes(out)


def read_rgb(path):
    """(width, height, pixels): pixels a list of (r, g, b) floats, row by row from the top."""
    with open(path, "rb") as f:
        d = f.read()
    if d[:4] != b"\x76\x2f\x31\x01":
        raise ValueError(path + ": not an EXR")
    header, i = _header(d)
    channels = _channels(header["channels"])
    compression = header["compression"][0]
    if compression not in _LINES or any(t != 2 for name, t in channels if name in "RGB"):
        raise ValueError(path + ": unsupported EXR (compression %d)" % compression)
    x0, y0, x1, y1 = struct.unpack("<4i", header["dataWindow"])
    w, h = x1 - x0 + 1, y1 - y0 + 1
    lines = _LINES[compression]
    offsets = struct.unpack_from("<%dQ" % ((h + lines - 1) // lines), d, i)
    planes = {c: [0.0] * (w * h) for c in "RGB"}
    for off in offsets:
        y, n = struct.unpack_from("<2i", d, off)
        raw = d[off + 8:off + 8 + n]
        rows = min(lines, y1 + 1 - y)
        if compression != 0 and n < rows * w * sum(_SIZE[t] for _, t in channels):
            raw = _unzip(raw)
        p = 0
        for r in range(rows):
            for name, t in channels:
                if name in planes:
                    values = array.array("f", raw[p:p + w * _SIZE[t]])
                    if sys.byteorder != "little":
                        values.byteswap()
                    row = (y - y0 + r) * w
                    planes[name][row:row + w] = values.tolist()
                p += w * _SIZE[t]
    return w, h, list(zip(planes["R"], planes["G"], planes["B"]))
