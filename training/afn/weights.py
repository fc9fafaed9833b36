# SPDX-License-Identifier: Apache-2.0
"""The afn weights archive (``.afnw``), shared by the training toolkit and the C++ core
(lib/core/nn/weights.cpp reads it with a bounds check on every field).

Layout, all integers little-endian::

    0   char[4]  magic "AFNW"
    4   u32      version (FORMAT_VERSION = 1)
    8   u32      tensor count N
    12  u32      metadata size M
    16  u8[M]    metadata: UTF-8 "key=value" lines ('\\n'-terminated), e.g. "variant=full"
    ..  N entries of the tensor table:
            u16 name size L, u8[L] name (the PyTorch state_dict key, e.g. "enc1.weight"),
            u8 dtype (1 = float32), u8 rank R (1..4), u32[R] dims (PyTorch order),
            u64 data offset (from the start of the file, multiple of 16), u64 data size in bytes
    ..  tensor data, float32 little-endian, row-major (PyTorch contiguous order)

A reader must reject: a wrong magic, an unknown version, any offset/size outside the file, a data
size that differs from 4 * prod(dims), an unknown dtype, duplicate names.
"""

import struct

import numpy as np

MAGIC = b"AFNW"
FORMAT_VERSION = 1
DTYPE_FLOAT32 = 1
ALIGN = 16


class WeightsFormatError(ValueError):
    """The file is not a valid afn weights archive."""


def dumps(tensors: dict, metadata: dict = None) -> bytes:
    """Serialise named float32 arrays (name -> numpy array or torch tensor) and string metadata."""
    meta = "".join(f"{k}={v}\n" for k, v in (metadata or {}).items()).encode("utf-8")
    arrays = []
    for name, t in tensors.items():
        a = t.detach().cpu().numpy() if hasattr(t, "detach") else np.asarray(t)
        a = np.ascontiguousarray(a, dtype="<f4")
        if not 1 <= a.ndim <= 4:
            raise WeightsFormatError(f"tensor '{name}' has rank {a.ndim} (1..4 supported)")
        arrays.append((name.encode("utf-8"), a))
    table_size = sum(2 + len(n) + 2 + 4 * a.ndim + 16 for n, a in arrays)
    pos = 16 + len(meta) + table_size
    offsets = []
    for _, a in arrays:
        pos = (pos + ALIGN - 1) // ALIGN * ALIGN
        offsets.append(pos)
        pos += a.nbytes
    out = bytearray(struct.pack("<4sIII", MAGIC, FORMAT_VERSION, len(arrays), len(meta)))
    out += meta
    for (name, a), off in zip(arrays, offsets):
        out += struct.pack("<H", len(name)) + name
        out += struct.pack("<BB", DTYPE_FLOAT32, a.ndim)
        out += struct.pack(f"<{a.ndim}I", *a.shape)
        out += struct.pack("<QQ", off, a.nbytes)
    for (_, a), off in zip(arrays, offsets):
        out += b"\0" * (off - len(out))
        out += a.tobytes()
    return bytes(out)


def loads(data: bytes):
    """Parse an archive; returns (dict name -> float32 numpy array, dict metadata)."""
    def need(pos, n, what):
        if pos + n > len(data):
            raise WeightsFormatError(f"invalid or corrupted weights: truncated {what}")

    need(0, 16, "header")
    magic, version, count, msize = struct.unpack_from("<4sIII", data, 0)
    if magic != MAGIC:
        raise WeightsFormatError("invalid or corrupted weights: bad magic (not an .afnw file)")
    if version != FORMAT_VERSION:
        raise WeightsFormatError(f"unsupported weights format version {version}")
    need(16, msize, "metadata")
    meta = {}
    for line in data[16:16 + msize].decode("utf-8").splitlines():
        if "=" in line:
            k, v = line.split("=", 1)
            meta[k] = v
    pos = 16 + msize
    tensors = {}
    for _ in range(count):
        need(pos, 2, "tensor table")
        (nlen,) = struct.unpack_from("<H", data, pos)
        need(pos + 2, nlen + 2, "tensor table")
        name = data[pos + 2:pos + 2 + nlen].decode("utf-8")
        dtype, rank = struct.unpack_from("<BB", data, pos + 2 + nlen)
        pos += 4 + nlen
        if dtype != DTYPE_FLOAT32 or not 1 <= rank <= 4:
            raise WeightsFormatError(f"invalid or corrupted weights: tensor '{name}' dtype/rank")
        need(pos, 4 * rank + 16, "tensor table")
        dims = struct.unpack_from(f"<{rank}I", data, pos)
        off, size = struct.unpack_from("<QQ", data, pos + 4 * rank)
        pos += 4 * rank + 16
        if size != 4 * int(np.prod(dims)) or off + size > len(data) or name in tensors:
            raise WeightsFormatError(f"invalid or corrupted weights: tensor '{name}'")
        tensors[name] = np.frombuffer(data, "<f4", int(np.prod(dims)), off).reshape(dims).copy()
    return tensors, meta


def save_model(path, model) -> None:
    """Write a model's state_dict and its AFNConfig (metadata) to ``path``."""
    cfg = model.cfg
    meta = {"format": "afn", "variant": cfg.variant, "enc": ",".join(map(str, cfg.enc)),
            "dec": ",".join(map(str, cfg.dec)), "refine": cfg.refine, "inputs": cfg.inputs}
    if cfg.spp != 1:     # absent = 1 spp (every older archive); model_set.h chooses by it
        meta["spp"] = cfg.spp
    if getattr(cfg, "quarter", False):   # absent = the paper's two scales
        meta["quarter"] = 1
    if getattr(cfg, "history", False):   # absent = the 13 inputs of every older archive
        meta["history"] = 1
    if getattr(cfg, "albedo_trust", False):  # absent = the paper's demodulation by the albedo
        meta["albedoTrust"] = 1
    with open(path, "wb") as f:
        f.write(dumps(model.state_dict(), meta))


def load_model(path, device="cpu"):
    """Read an archive written by save_model; returns an AFN in eval mode."""
    import torch

    from .model import AFNConfig, make_model
    with open(path, "rb") as f:
        tensors, meta = loads(f.read())
    cfg = AFNConfig(variant=meta.get("variant", "full"),
                    enc=tuple(int(v) for v in meta.get("enc", "16,32,64").split(",")),
                    dec=tuple(int(v) for v in meta.get("dec", "32,24").split(",")),
                    refine=int(meta.get("refine", 16)),
                    inputs=meta.get("inputs", "albedo,normal,depth,temporal"),
                    spp=int(meta.get("spp", 1)), quarter=meta.get("quarter", "0") == "1",
                    history=meta.get("history", "0") == "1",
                    albedo_trust=meta.get("albedoTrust", "0") == "1")
    model = make_model(cfg)
    model.load_state_dict({k: torch.from_numpy(v) for k, v in tensors.items()})
    return model.to(device).eval()
