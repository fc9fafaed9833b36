# SPDX-License-Identifier: Apache-2.0
"""EXR post-processing of generated sequences (OpenImageIO, /usr/bin/python3).

* :func:`splice_vector`: copy the Vector channels of an unblurred render into a motion-blurred
  frame (Cycles writes an all-zero Vector pass when motion blur is on) and mark the file with the
  header attribute ``afn:vector_source``.
* :func:`average_parts`: average K independent reference parts into one reference whose
  ``cycles.<layer>.samples`` header is the sum of the parts' samples.
* :func:`sample_weighted_mean`: a training target from independent renders of one frame (Combined
  only), each weighted by its sample count, as if one render had taken all their samples.
* :func:`samples`: the sample count Blender recorded in a file's header.

Every write goes to a temporary name in the same folder and is renamed when complete.
"""

import os

import numpy as np
import OpenImageIO as oiio

VECTOR_SOURCE_ATTR = "afn:vector_source"
PARTS_ATTR = "afn:reference_parts"
TARGET_ATTR = "afn:target"


def read(path):
    """(ImageSpec, float32 pixels (H, W, C)) of ``path``."""
    inp = oiio.ImageInput.open(path)
    if inp is None:
        raise OSError("cannot open %s: %s" % (path, oiio.geterror()))
    try:
        spec = inp.spec()
        pixels = inp.read_image(0, spec.nchannels, oiio.FLOAT)
    finally:
        inp.close()
    if pixels is None:
        raise OSError("cannot read %s" % path)
    return spec, np.asarray(pixels, np.float32).reshape(spec.height, spec.width, spec.nchannels)


def header(path):
    """ImageSpec of ``path`` (header only)."""
    inp = oiio.ImageInput.open(path)
    if inp is None:
        raise OSError("cannot open %s: %s" % (path, oiio.geterror()))
    spec = inp.spec()
    inp.close()
    return spec


def write(path, spec, pixels):
    """Write ``pixels`` with ``spec`` (channel names, per-channel formats, attributes) atomically."""
    tmp = path[:-4] + ".tmp.exr"
    out = oiio.ImageOutput.create(tmp)
    if out is None or not out.open(tmp, spec):
        raise OSError("cannot write %s: %s" % (tmp, oiio.geterror()))
    ok = out.write_image(np.ascontiguousarray(pixels, np.float32))
    out.close()
    if not ok:
        raise OSError("cannot write %s" % tmp)
    os.replace(tmp, path)


def samples(path):
    """Sample count in the header (``cycles.<layer>.samples``), or None when absent."""
    spec = header(path)
    for attr in spec.extra_attribs:
        if attr.name.startswith("cycles.") and attr.name.endswith(".samples"):
            return int(attr.value)
    return None


def _samples_attr(spec):
    for attr in spec.extra_attribs:
        if attr.name.startswith("cycles.") and attr.name.endswith(".samples"):
            return attr.name
    return "cycles.ViewLayer.samples"


def vector_channels(names):
    """Indices of the ``<layer>.Vector.X/Y/Z/W`` channels in ``names``."""
    idx = [i for i, n in enumerate(names) if ".Vector." in n or n.startswith("Vector.")]
    if len(idx) != 4:
        raise KeyError("expected 4 Vector channels, found %d" % len(idx))
    return idx


def splice_vector(frame_path, vector_path, note):
    """Replace the Vector channels of ``frame_path`` with those of ``vector_path``.

    Returns False (and changes nothing) when the frame already carries ``afn:vector_source``.
    """
    spec = header(frame_path)
    if spec.getattribute(VECTOR_SOURCE_ATTR) is not None:
        return False
    spec, pixels = read(frame_path)
    vspec, vpix = read(vector_path)
    if (vspec.width, vspec.height) != (spec.width, spec.height):
        raise ValueError("size mismatch: %s vs %s" % (frame_path, vector_path))
    dst = vector_channels(list(spec.channelnames))
    src = vector_channels(list(vspec.channelnames))
    pixels[..., dst] = vpix[..., src]
    spec.attribute(VECTOR_SOURCE_ATTR, note)
    write(frame_path, spec, pixels)
    return True


def average_parts(part_paths, out_path):
    """Average independent reference parts into ``out_path``; header samples = sum of parts."""
    total, acc, spec = 0, None, None
    for path in part_paths:
        s, pix = read(path)
        spec = spec or s
        acc = pix.astype(np.float64) if acc is None else acc + pix
        total += samples(path) or 0
    spec.attribute(_samples_attr(spec), str(total))
    spec.attribute(PARTS_ATTR, "%d independent parts of %d samples averaged"
                   % (len(part_paths), total // max(1, len(part_paths))))
    write(out_path, spec, (acc / len(part_paths)).astype(np.float32))
    return total


def combined_channels(names):
    """Indices of ``<layer>.Combined.R/G/B/A`` in ``names``."""
    idx = [next(i for i, n in enumerate(names) if n.endswith("Combined." + c)) for c in "RGBA"]
    return idx


def sample_weighted_mean(paths, out_path, note):
    """Mean of the Combined passes of ``paths`` weighted by their header sample counts.

    Cycles' pixel value is the mean of its samples, so the result equals a render with the summed
    samples. Writes Combined RGBA as float32 with ``cycles.<layer>.samples`` = the sum and
    ``afn:target`` = ``note``; returns the sum.
    """
    acc, total, first = None, 0, None
    for path in paths:
        spec, pix = read(path)
        n = samples(path)
        if not n:
            raise ValueError("no sample count in the header of %s" % path)
        rgba = pix[..., combined_channels(list(spec.channelnames))].astype(np.float64) * n
        acc = rgba if acc is None else acc + rgba
        total += n
        first = first or spec
    out = oiio.ImageSpec(first.width, first.height, 4, oiio.FLOAT)
    out.channelnames = tuple(first.channelnames[i]
                             for i in combined_channels(list(first.channelnames)))
    out.attribute("compression", "zip")
    out.attribute(_samples_attr(first), str(total))
    out.attribute(TARGET_ATTR, note)
    write(out_path, out, (acc / total).astype(np.float32))
    return total
