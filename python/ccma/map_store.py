"""Finished chunks of a batch (a workspace map, a design sweep) kept in a Zarr
directory as they complete, so that a run that is interrupted (a killed
client, Ctrl-C, a lost laptop connection) resumes where it stopped.

    store = MapStore(path, key={"model": text, "ranges": ..., ...}, num_chunks=n)
    store.done()             # indices of the chunks already complete
    store.read(i)            # dict of NumPy arrays and string lists, or None
    store.write(i, result)   # as soon as chunk i is computed

Layout (Debian's python3-zarr, format 2):
    <path>/.zattrs           {"ccma_store": 1, "key": sha256 of the arguments, "num_chunks": n}
    <path>/chunks/<i>/       one array per numeric field, string lists in attrs
    <path>/chunks/<i>/.zattrs  {"fields": ..., "strings": ..., "sha256": ..., "complete": true}

A chunk counts as done only when its `complete` marker is set, which is
written last, and when its arrays still hash to the recorded sha256: a chunk
half-written by a killed process has no marker, a corrupted one fails the
hash, and both are computed again. A store made for other arguments is
refused (ValueError), never mixed. Reference: docs/workspace.md, "On a cluster".
"""
import hashlib
import json
import os

import numpy as _np

_FORMAT = 1


def arguments_key(arguments):
    """sha256 (hex) of the JSON of `arguments` (keys sorted): what a store is for."""
    text = json.dumps(arguments, sort_keys=True, separators=(",", ":"), default=str)
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def _digest(arrays, strings):
    h = hashlib.sha256()
    for name in sorted(arrays):
        a = _np.ascontiguousarray(arrays[name])
        h.update(name.encode())
        h.update(str(a.dtype).encode())
        h.update(repr(a.shape).encode())
        h.update(a.tobytes())
    h.update(json.dumps(strings, sort_keys=True).encode("utf-8"))
    return h.hexdigest()


class MapStore:
    """The Zarr directory `path` holding the chunks of one batch (see the module)."""

    def __init__(self, path, key, num_chunks):
        import zarr  # Debian's python3-zarr; only needed by callers that pass store=

        self.path = os.fspath(path)
        self.num_chunks = int(num_chunks)
        digest = arguments_key(key)
        self._root = zarr.open_group(self.path, mode="a")
        attrs = self._root.attrs.asdict()
        if attrs:
            if attrs.get("ccma_store") != _FORMAT or attrs.get("key") != digest or \
                    attrs.get("num_chunks") != self.num_chunks:
                raise ValueError(f"store {self.path!r} holds another batch (other arguments, model or "
                                 "format): use a new directory, or delete this one to start again")
        else:
            self._root.attrs.update({"ccma_store": _FORMAT, "key": digest, "num_chunks": self.num_chunks})
        self._chunks = self._root.require_group("chunks")

    def done(self):
        """Indices of the chunks whose write completed (not yet hash-checked)."""
        out = set()
        for name in self._chunks.group_keys():
            if name.isdigit() and 0 <= int(name) < self.num_chunks and \
                    self._chunks[name].attrs.get("complete") is True:
                out.add(int(name))
        return out

    def read(self, index):
        """Chunk `index` as written, or None when it is missing, incomplete or corrupted."""
        name = str(int(index))
        try:
            group = self._chunks[name]
            attrs = group.attrs.asdict()
            if attrs.get("complete") is not True:
                return None
            arrays = {field: group[field][...] for field in attrs["fields"]}
            strings = attrs["strings"]
            if _digest(arrays, strings) != attrs["sha256"]:
                return None
        except Exception:  # noqa: BLE001 - any unreadable chunk is recomputed, whatever broke it
            return None
        out = dict(arrays)
        out.update(strings)
        return out

    def write(self, index, result):
        """Writes chunk `index` (a dict of arrays and lists of str); the marker last."""
        name = str(int(index))
        if name in self._chunks:
            del self._chunks[name]  # a half-written or corrupted earlier attempt
        group = self._chunks.create_group(name)
        arrays, strings = {}, {}
        for field, value in result.items():
            if isinstance(value, list):
                strings[field] = [str(v) for v in value]
            else:
                arrays[field] = _np.asarray(value)
        for field, a in arrays.items():
            # One Zarr chunk per array (a chunk of the batch is small); at least 1 per axis.
            group.array(field, a, chunks=tuple(max(1, n) for n in a.shape) or None)
        group.attrs.update({"fields": sorted(arrays), "strings": strings,
                            "sha256": _digest(arrays, strings)})
        group.attrs["complete"] = True
