# SPDX-License-Identifier: Apache-2.0
"""Check an OFX bundle as hosts read it: a well-formed Info.plist with the CFBundle keys, the
binary it names, and a PNG icon Contents/Resources/<CFBundleIdentifier>.png that decodes.

Usage: check_bundle.py BUNDLE_DIR [BUNDLE_DIR ...]   (e.g. the build tree's and an installed one)
"""
import plistlib
import struct
import sys
import zlib
from pathlib import Path

REQUIRED_KEYS = ("CFBundleDevelopmentRegion", "CFBundleExecutable", "CFBundleIdentifier",
                 "CFBundleInfoDictionaryVersion", "CFBundlePackageType",
                 "CFBundleShortVersionString", "CFBundleVersion", "CFBundleSignature")


def png_size(data):
    """Width, height of an 8-bit RGBA PNG after checking every chunk's CRC and the pixel data."""
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError("not a PNG signature")
    pos, chunks, idat = 8, [], b""
    while pos < len(data):
        (length,) = struct.unpack(">I", data[pos:pos + 4])
        kind, body = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + length]
        (crc,) = struct.unpack(">I", data[pos + 8 + length:pos + 12 + length])
        if zlib.crc32(kind + body) != crc:
            raise ValueError(f"bad CRC in chunk {kind!r}")
        chunks.append(kind)
        if kind == b"IDAT":
            idat += body
        pos += 12 + length
    if chunks[0] != b"IHDR" or chunks[-1] != b"IEND":
        raise ValueError(f"chunk order {chunks}")
    ihdr = data[16:29]
    width, height, depth, colour = struct.unpack(">IIBB", ihdr[:10])
    if (depth, colour) != (8, 6):
        raise ValueError(f"depth {depth} colour type {colour}, expected 8-bit RGBA")
    raw = zlib.decompress(idat)
    if len(raw) != height * (1 + 4 * width):
        raise ValueError(f"{len(raw)} bytes of pixel data for {width}x{height}")
    return width, height


def check(bundle):
    contents = Path(bundle) / "Contents"
    with open(contents / "Info.plist", "rb") as f:
        info = plistlib.load(f)  # raises on a malformed plist
    missing = [k for k in REQUIRED_KEYS if k not in info]
    if missing:
        raise ValueError(f"Info.plist lacks {missing}")
    if info["CFBundlePackageType"] != "BNDL":
        raise ValueError("CFBundlePackageType is not BNDL")
    binary = contents / "Linux-x86-64" / info["CFBundleExecutable"]
    if not binary.is_file():
        raise ValueError(f"CFBundleExecutable {binary} does not exist")
    icon = contents / "Resources" / (info["CFBundleIdentifier"] + ".png")
    width, height = png_size(icon.read_bytes())
    print(f"{bundle}: {info['CFBundleIdentifier']} {info['CFBundleShortVersionString']}, "
          f"icon {width}x{height}")


def main(argv):
    if len(argv) < 2:
        print(__doc__, file=sys.stderr)
        return 2
    for bundle in argv[1:]:
        try:
            check(bundle)
        except (OSError, ValueError, plistlib.InvalidFileException) as e:
            print(f"check_bundle ERROR: {bundle}: {e}", file=sys.stderr)
            return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
