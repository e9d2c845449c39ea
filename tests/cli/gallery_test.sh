#!/usr/bin/env bash
# The README's gallery can be made again: docs/gallery/make-gallery.sh renders into a fresh folder, and
# every image README.md shows from docs/gallery/ comes out a valid PNG of the committed image's size
# that is not one flat colour.
#
#   tests/cli/gallery_test.sh FACET_BINARY SOURCE_DIR WORK_DIR
#
# Exit 77 (skipped) without python3, which checks the PNG files.
set -euo pipefail

if [[ $# -ne 3 ]]; then
    echo "usage: $0 FACET_BINARY SOURCE_DIR WORK_DIR" >&2
    exit 2
fi
facet=$1
source_dir=$2
work=$3

if ! command -v python3 >/dev/null; then
    echo "skipped: the test needs python3 (to read the PNG files)"
    exit 77
fi

rm -rf "$work"
mkdir -p "$work"
# set -e: a failure of the script (and so of facet) fails the test.
bash "$source_dir/docs/gallery/make-gallery.sh" "$facet" "$work"

python3 - "$source_dir" "$work" <<'PY'
import re, struct, sys, zlib
from pathlib import Path

source, work = Path(sys.argv[1]), Path(sys.argv[2])

def read_png(path):
    """(width, height, channels, rows of bytes) of an 8-bit, non-interlaced PNG; raises on anything invalid."""
    data = path.read_bytes()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError("no PNG signature")
    pos, idat, header, ended = 8, b"", None, False
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if len(body) != length:
            raise ValueError("truncated chunk")
        (crc,) = struct.unpack(">I", data[pos + 8 + length:pos + 12 + length])
        if zlib.crc32(kind + body) != crc:
            raise ValueError(f"bad CRC in chunk {kind!r}")
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        elif kind == b"IEND":
            ended = True
            break
        pos += 12 + length
    if header is None or not ended or not idat:
        raise ValueError("missing IHDR, IDAT or IEND")
    width, height, depth, colour, _, _, interlace = header
    channels = {0: 1, 2: 3, 4: 2, 6: 4}.get(colour)
    if depth != 8 or channels is None or interlace != 0:
        raise ValueError(f"unexpected format: depth {depth}, colour type {colour}, interlace {interlace}")
    raw = zlib.decompress(idat)
    stride = width * channels
    if len(raw) != height * (stride + 1):
        raise ValueError("image data of the wrong size")
    rows, previous = [], bytearray(stride)
    for y in range(height):
        kind = raw[y * (stride + 1)]
        row = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = row[i - channels] if i >= channels else 0
            b = previous[i]
            c = previous[i - channels] if i >= channels else 0
            if kind == 1:
                row[i] = (row[i] + a) & 255
            elif kind == 2:
                row[i] = (row[i] + b) & 255
            elif kind == 3:
                row[i] = (row[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                row[i] = (row[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
            elif kind != 0:
                raise ValueError(f"unknown filter {kind} in row {y}")
        rows.append(bytes(row))
        previous = row
    return width, height, channels, rows

readme = (source / "README.md").read_text()
names = sorted(set(re.findall(r"docs/gallery/([A-Za-z0-9_.-]+\.png)", readme)))
if not names:
    sys.exit("README.md shows no image of docs/gallery/")
failures = []
for name in names:
    made, committed = work / name, source / "docs" / "gallery" / name
    try:
        if not made.is_file():
            raise ValueError("make-gallery.sh did not write it")
        if not committed.is_file():
            raise ValueError(f"README.md shows {committed}, which is not in the repository")
        width, height, channels, rows = read_png(made)
        expected = read_png(committed)[:2]
        if (width, height) != expected:
            raise ValueError(f"{width}x{height}, the committed image is {expected[0]}x{expected[1]}")
        first = rows[0][:channels]
        if all(row == first * width for row in rows):
            raise ValueError("every pixel has one colour")
        print(f"{name}: {width}x{height}, not flat")
    except Exception as error:  # noqa: BLE001 - every problem is reported with its file
        failures.append(f"{name}: {error}")
if failures:
    sys.exit("\n".join(failures))
print(f"{len(names)} gallery images rendered and checked")
PY
