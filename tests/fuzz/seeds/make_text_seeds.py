#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Write the hand-made seeds of fuzz_frame_pattern and fuzz_weights.

fuzz_frame_pattern reads its input with FuzzedDataProvider: the last byte picks the operation
(0 range, 1 pattern, 2 --aov override), a pattern case then takes two frame numbers from the 4-byte
groups before it (each an offset from -1e9), and the text is what remains at the front.
fuzz_weights takes the raw bytes of an .afnw archive: the small committed test archives plus a few
truncated and inconsistent headers. Run with: /usr/bin/python3 tests/fuzz/seeds/make_text_seeds.py
"""
import os
import shutil
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
CORPUS = os.path.join(HERE, "..", "corpus")
DATA = os.path.join(HERE, "..", "..", "data", "afn_parity")


def frame_bytes(frame):
    return struct.pack("<I", frame + 1000000000)


def write(target, name, data):
    os.makedirs(os.path.join(CORPUS, target), exist_ok=True)
    with open(os.path.join(CORPUS, target, name), "wb") as f:
        f.write(data)


def frame_pattern():
    for i, text in enumerate(["1-10", "1-10x2", "3,5,7", "1-4,10", "-5--1", "10-1", "0"]):
        write("fuzz_frame_pattern", f"range_{i}", text.encode() + b"\x00")
    patterns = ["shot.####.exr", "shot.#.exr", "shot.@@@.exr", "shot.%04d.exr", "shot.%d.exr",
                "plain.exr", "a#b@c%02d.exr"]
    for i, text in enumerate(patterns):
        write("fuzz_frame_pattern", f"pattern_{i}",
              text.encode() + frame_bytes(-7) + frame_bytes(12) + b"\x01")
    overrides = ["albedo=diffuse.R,diffuse.G,diffuse.B", "normal.space=camera", "depth=Z",
                 "motion.yUp=true", "colour=beauty"]
    for i, text in enumerate(overrides):
        write("fuzz_frame_pattern", f"override_{i}", text.encode() + b"\x02")


def weights():
    for name in ["weights_fusion.afnw", "weights_full.afnw"]:
        shutil.copy(os.path.join(DATA, name), os.path.join(CORPUS, "fuzz_weights", name))
    header = b"AFNW" + struct.pack("<III", 1, 1, 12) + b"variant=ta\n\n"
    tensor = struct.pack("<H", 4) + b"enc1" + bytes([1, 2]) + struct.pack("<II", 2, 2)
    offset = len(header) + len(tensor) + 16
    write("fuzz_weights", "one_tensor.afnw",
          header + tensor + struct.pack("<QQ", offset, 16) + struct.pack("<4f", 1, 2, 3, 4))
    write("fuzz_weights", "truncated_table.afnw", header + tensor[:5])
    write("fuzz_weights", "bad_version.afnw", b"AFNW" + struct.pack("<III", 7, 0, 0))
    write("fuzz_weights", "lfs_pointer.afnw", b"version https://git-lfs.github.com/spec/v1\n")


if __name__ == "__main__":
    os.makedirs(os.path.join(CORPUS, "fuzz_weights"), exist_ok=True)
    frame_pattern()
    weights()
