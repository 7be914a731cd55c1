"""The pixels of a PNG relief wrote (8-bit RGB or RGBA), for the CLI tests' scripts: no library
needed beyond Python's own."""
import struct
import zlib


def png_rgb(path):
    b = open(path, 'rb').read()
    i, idat, w, h = 8, b'', 0, 0
    while i < len(b):
        n, kind = struct.unpack('>I4s', b[i:i + 8])
        if kind == b'IHDR':
            w, h, depth, ctype = struct.unpack('>IIBB', b[i + 8:i + 18])
            assert depth == 8 and ctype in (2, 6), (path, depth, ctype)
            ch = 3 if ctype == 2 else 4
        elif kind == b'IDAT':
            idat += b[i + 8:i + 8 + n]
        i += 12 + n
    raw, rows, prev, stride = zlib.decompress(idat), [], bytearray(w * ch), w * ch
    for y in range(h):
        f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for x in range(stride):
            a = line[x - ch] if x >= ch else 0
            c = prev[x - ch] if x >= ch else 0
            p = a + prev[x] - c
            pred = [0, a, prev[x], (a + prev[x]) // 2,
                    a if abs(p - a) <= abs(p - prev[x]) and abs(p - a) <= abs(p - c) else prev[x] if abs(p - prev[x]) <= abs(p - c) else c][f]
            line[x] = (line[x] + pred) & 255
        rows.append(line)
        prev = line
    return w, h, ch, rows
