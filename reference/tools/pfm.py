"""PFM reading shared by the AO study scripts beside it (they import it from
their own folder)."""
import array
import sys


def read_pfm(path):
    """First channel, rows bottom to top as stored (the pixel grid's order)."""
    with open(path, "rb") as f:
        kind = f.readline().strip()
        width, height = (int(v) for v in f.readline().split())
        scale = float(f.readline())
        data = array.array("f")
        data.frombytes(f.read())
    if (scale < 0) != (sys.byteorder == "little"):
        data.byteswap()
    channels = 3 if kind == b"PF" else 1
    return width, height, [data[i * channels] for i in range(width * height)]
