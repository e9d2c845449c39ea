#!/usr/bin/env python3
"""Deflate on a render's PNG pixel data: zlib (the levels and strategies Facet could use) against
libdeflate, each timed in CPU time on one thread (fastest of --rounds), with the bytes each gives.
The input is the filtered pixel data of a PNG written by Facet (its IDAT stream inflated), which is
what Facet's writer deflates.

    build/src/facet render MODEL --width 1920 --height 1080 -o out/e2e.png -q
    python3 src/bench/png_deflate.py out/e2e.png [--rounds 15]
"""
import argparse
import ctypes
import ctypes.util
import struct
import time
import zlib

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("png")
parser.add_argument("--rounds", type=int, default=15)
args = parser.parse_args()

data = open(args.png, "rb").read()
idat = bytearray()
at = 8
while at + 12 <= len(data):
    (length,) = struct.unpack(">I", data[at:at + 4])
    if data[at + 4:at + 8] == b"IDAT":
        idat += data[at + 8:at + 8 + length]
    at += 12 + length
filtered = zlib.decompress(bytes(idat))


def fastest(compress):
    best, size = float("inf"), 0
    for _ in range(args.rounds):
        start = time.thread_time()
        size = compress()
        best = min(best, time.thread_time() - start)
    return best, size


rows = []
for level, strategy, name in [(1, zlib.Z_DEFAULT_STRATEGY, ""), (2, zlib.Z_DEFAULT_STRATEGY, ""),
                              (6, zlib.Z_DEFAULT_STRATEGY, ""), (1, zlib.Z_RLE, ", run-length matches only")]:
    def compress():
        stream = zlib.compressobj(level, zlib.DEFLATED, 15, 8, strategy)
        return len(stream.compress(filtered) + stream.flush())
    rows.append((f"zlib level {level}{name}", *fastest(compress)))

library = ctypes.util.find_library("deflate")
if library:
    libdeflate = ctypes.CDLL(library)
    libdeflate.libdeflate_alloc_compressor.restype = ctypes.c_void_p
    libdeflate.libdeflate_zlib_compress.restype = ctypes.c_size_t
    libdeflate.libdeflate_zlib_compress.argtypes = [ctypes.c_void_p, ctypes.c_char_p, ctypes.c_size_t,
                                                    ctypes.c_void_p, ctypes.c_size_t]
    libdeflate.libdeflate_free_compressor.argtypes = [ctypes.c_void_p]
    out = ctypes.create_string_buffer(len(filtered) + len(filtered) // 8 + 1024)
    for level in (1, 2, 3, 6):
        compressor = libdeflate.libdeflate_alloc_compressor(level)
        rows.append((f"libdeflate level {level}", *fastest(
            lambda: libdeflate.libdeflate_zlib_compress(compressor, filtered, len(filtered), out, len(out)))))
        libdeflate.libdeflate_free_compressor(compressor)
else:
    print("libdeflate not found: zlib only")

print(f"{len(filtered)} bytes of filtered pixel data, CPU time on one thread, fastest of {args.rounds}")
for name, seconds, size in rows:
    print(f"{name:44} {seconds * 1000:7.2f} ms {size:10,d} bytes")
