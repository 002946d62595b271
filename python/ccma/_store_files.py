"""The files of a Zarr store that someone else may have written, read without
trusting them (python/ccma/map_store.py; docs/python.md, "A store is data").

zarr decodes an array the way its `.zarray` says: dtype "|O" with a `pickle`
filter or object codec unpickles the chunk's bytes, which runs any code they
name. So nothing here asks zarr to read: every file goes through
`read_regular` (a regular file, opened without following a link, within a
size bound), JSON is parsed with `json`, and every array's metadata must be
exactly what ccma writes (`check_array_meta`) before any chunk is decoded,
by blosc, into a buffer of the size the checked shape implies.

Two kinds of trouble, told apart:
- hostile (HostileStore, a ValueError naming the store and the array): a
  link, FIFO, device or directory where a file belongs, a file beyond its
  bound, metadata ccma never writes (another dtype, codec, filter, order,
  chunking). Reading stops: the store is not ccma's.
- damaged (None from the readers): a file missing or unparsable, a chunk
  that does not decompress to its shape. The caller computes it again.
"""
import json
import os
import stat
import struct

import numpy as _np

# Bounds: what ccma itself writes stays far below them.
MAX_META_BYTES = 1 << 20  # a .zgroup, a .zarray, the store's .zattrs
MAX_ATTRS_BYTES = 64 << 20  # a chunk's .zattrs: its string lists (one warning per sample)
MAX_FIELDS = 256  # arrays in one chunk (a workspace tile has 34)
MAX_NDIM = 8
# c-blosc 1.x cannot compress more than INT_MAX - 16 bytes in one block, so
# no chunk ccma writes is larger; lz4 never compresses better than 255:1.
MAX_ARRAY_BYTES = (1 << 31) - 1 - 16
MAX_RATIO = 256
_BLOSC_HEADER = 16

# The only dtypes ccma stores: bool, integers and floats, little-endian.
DTYPES = frozenset(["|b1", "|i1", "|u1", "<i2", "<i4", "<i8", "<u2", "<u4", "<u8", "<f4", "<f8"])
# zarr's default compressor on Debian's python3-zarr 2.13 (numcodecs 0.11),
# the one MapStore.write gets; zarr writes null for a 0-d array.
COMPRESSOR = {"id": "blosc", "cname": "lz4", "clevel": 5, "shuffle": 1, "blocksize": 0}
_ARRAY_KEYS = {"chunks", "compressor", "dtype", "fill_value", "filters", "order", "shape", "zarr_format"}


class HostileStore(ValueError):
    """A store holding what ccma never writes: refused, never read further."""


def read_regular(path, limit, store, what):
    """The bytes of `path` (a regular file of at most `limit` bytes, not a link),
    or None when it does not exist; HostileStore for anything else."""
    try:
        if not stat.S_ISREG(os.lstat(path).st_mode):  # never open a device or a FIFO
            raise HostileStore(f"store {store!r}: {what} is not a regular file (a link, FIFO or device)")
        fd = os.open(path, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK | getattr(os, "O_CLOEXEC", 0))
    except FileNotFoundError:
        return None
    except OSError as e:  # ELOOP: a link; ENXIO: a FIFO or socket without a writer
        raise HostileStore(f"store {store!r}: {what} is not a regular file ({e.strerror})") from None
    with os.fdopen(fd, "rb") as f:
        info = os.fstat(f.fileno())
        if not stat.S_ISREG(info.st_mode):
            raise HostileStore(f"store {store!r}: {what} is not a regular file")
        if info.st_size > limit:
            raise HostileStore(f"store {store!r}: {what} has {info.st_size} bytes; at most {limit} are allowed")
        data = f.read(limit + 1)
    if len(data) > limit:  # grew while read
        raise HostileStore(f"store {store!r}: {what} has more than {limit} bytes")
    return data


def read_json(path, limit, store, what):
    """The JSON value in `path`, or None when it is missing or not JSON (damaged)."""
    data = read_regular(path, limit, store, what)
    if data is None:
        return None
    try:
        return json.loads(data.decode("utf-8"))
    except (ValueError, RecursionError):
        return None


def real_directory(path, store, what):
    """Whether `path` is a directory (False when missing); HostileStore for a
    link or anything else that is not a directory."""
    try:
        mode = os.lstat(path).st_mode
    except FileNotFoundError:
        return False
    if not stat.S_ISDIR(mode):
        raise HostileStore(f"store {store!r}: {what} is not a directory (a link or a file)")
    return True


def check_group(path, store, what, root=False):
    """A group folder: a real directory (the `root` the user named may be a link
    to one) whose .zgroup, if any, says format 2."""
    if root:
        if not os.path.isdir(path):
            raise HostileStore(f"store {store!r} is not a directory")
    elif not real_directory(path, store, what):
        return False
    meta = read_json(os.path.join(path, ".zgroup"), MAX_META_BYTES, store, what + "/.zgroup")
    if meta is not None and meta != {"zarr_format": 2}:
        raise HostileStore(f"store {store!r}: {what}/.zgroup is not a Zarr format 2 group")
    if os.path.lexists(os.path.join(path, ".zarray")):
        raise HostileStore(f"store {store!r}: {what} holds an array where a group belongs")
    return True


def plain_name(name):
    """Whether `name` can be an array folder's name: printable (it goes into
    messages), no separator, no dot file."""
    return 0 < len(name) <= 255 and name.isprintable() and "/" not in name and "\\" not in name and \
        not name.startswith(".")


def _is_count(n):
    return isinstance(n, int) and not isinstance(n, bool) and n >= 0


def check_array_meta(meta, store, what):
    """(dtype, shape, compressed) of an array whose `.zarray` holds exactly what
    MapStore.write makes: a dtype of DTYPES, C order, no filters, COMPRESSOR
    (or none), one chunk covering the array; HostileStore otherwise."""
    def refuse(why):
        raise HostileStore(f"store {store!r}: array {what}: {why}; ccma writes no such array "
                           "(refused without reading it: a store is data, not code)")

    if not isinstance(meta, dict) or set(meta) - {"dimension_separator"} != _ARRAY_KEYS:
        refuse("unexpected .zarray keys")
    if meta["zarr_format"] != 2 or meta.get("dimension_separator", ".") != ".":
        refuse("not Zarr format 2 with '.' separators")
    if not isinstance(meta["dtype"], str) or meta["dtype"] not in DTYPES:
        refuse(f"dtype {str(meta['dtype'])[:40]!r} is not a plain bool, integer or float")
    if meta["filters"] is not None:
        refuse("filters are set")
    if meta["compressor"] is not None and meta["compressor"] != COMPRESSOR:
        refuse("compressor is not blosc lz4 as zarr writes it")
    if meta["order"] != "C":
        refuse("order is not C")
    shape, chunks = meta["shape"], meta["chunks"]
    if not isinstance(shape, list) or len(shape) > MAX_NDIM or not all(_is_count(n) for n in shape):
        refuse("shape is not a list of counts")
    if chunks != [max(1, n) for n in shape]:
        refuse("not one chunk covering the array")
    dtype = _np.dtype(meta["dtype"])
    if int(_np.prod(shape, dtype=object)) * dtype.itemsize > MAX_ARRAY_BYTES:
        refuse(f"more than {MAX_ARRAY_BYTES} bytes")
    fill = meta["fill_value"]
    if fill is not None and not isinstance(fill, (bool, int, float)) and fill not in ("NaN", "Infinity", "-Infinity"):
        refuse("fill_value is not a number")
    return dtype, tuple(shape), meta["compressor"] is not None


def read_array(folder, dtype, shape, compressed, store, what):
    """The array of a checked .zarray (check_array_meta) from its one chunk
    file, or None when that file is missing or does not decode to `shape`."""
    nbytes = int(_np.prod(shape, dtype=object)) * dtype.itemsize
    if 0 in shape:
        return _np.empty(shape, dtype)  # zarr writes no chunk file for an empty array
    name = ".".join("0" for _ in shape) or "0"
    limit = nbytes + 16 * 1024 if compressed else nbytes  # blosc adds at most 16 bytes
    data = read_regular(os.path.join(folder, name), min(limit, MAX_ARRAY_BYTES + 1024), store, f"{what}/{name}")
    if data is None:
        return None
    if not compressed:
        return _np.frombuffer(data, dtype).reshape(shape).copy() if len(data) == nbytes else None
    if len(data) < _BLOSC_HEADER:
        return None
    claimed, _, cbytes = struct.unpack_from("<III", data, 4)
    if claimed != nbytes or cbytes != len(data) or nbytes > MAX_RATIO * len(data) + 4096:
        return None
    from numcodecs import blosc  # Debian's python3-numcodecs, with zarr

    out = _np.empty(shape, dtype)
    try:
        blosc.decompress(data, out)
    except (RuntimeError, ValueError):
        return None
    return out
