"""The smallest PNG writer the asset scripts need (numpy and Pillow are not installed here):
8-bit RGB or RGBA rows, zlib-compressed, no filtering."""
import struct
import zlib


def png(width, height, rows, channels=3):
    """rows: `height` lists of width × channels bytes (0–255), top row first."""
    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))
    raw = b"".join(b"\0" + bytes(row) for row in rows)
    colour_type = {3: 2, 4: 6}[channels]  # PNG's truecolour, truecolour with alpha
    header = struct.pack(">IIBBBBB", width, height, 8, colour_type, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) +
            chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))
