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
    <path>/chunks/<i>/.zattrs  {"fields": ..., "strings": ..., "key": ..., "sha256": ..., "complete": true}

A chunk counts as done only when its `complete` marker is set, which is
written last, and when its arrays still hash to the recorded sha256: a chunk
half-written by a killed process has no marker, a corrupted one fails the
hash, and both are computed again. A store made for other arguments is
refused (ValueError), never mixed. Every chunk carries the key of the batch
it belongs to, inside its sha256 too: a chunk copied from another store (or
left in a store whose root .zattrs was deleted) is computed again, with a
UserWarning naming it.

A store may come from someone else (a shared cluster folder), so it is read
as data, never through zarr's decoding (python/ccma/_store_files.py): every
file must be a regular file within its bound, and every array's `.zarray`
exactly what `write` makes (bool, integer or float, blosc lz4, no filters,
one chunk) before a byte of it is decoded. Anything else (a pickled object
array, a link, a FIFO) is refused with a ValueError naming the store and the
array, not computed again: such a store was not written by ccma.
Reference: docs/workspace.md, "On a cluster"; docs/python.md.
"""
import hashlib
import json
import os
import shutil
import warnings

import numpy as _np

from . import _store_files as _files

_FORMAT = 1


def arguments_key(arguments):
    """sha256 (hex) of the JSON of `arguments` (keys sorted): what a store is for."""
    text = json.dumps(arguments, sort_keys=True, separators=(",", ":"), default=str)
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def _digest(arrays, strings, key):
    """sha256 of a chunk's arrays and strings and of `key`, its batch's key."""
    h = hashlib.sha256()
    h.update(key.encode("utf-8"))
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
        digest = self._key = arguments_key(key)
        attrs = self._existing_attrs()  # checked before zarr opens anything
        self._root = zarr.open_group(self.path, mode="a")
        if attrs:
            if attrs.get("ccma_store") != _FORMAT or attrs.get("key") != digest or \
                    attrs.get("num_chunks") != self.num_chunks:
                raise ValueError(f"store {self.path!r} holds another batch (other arguments, model or "
                                 "format): use a new directory, or delete this one to start again")
        else:
            self._root.attrs.update({"ccma_store": _FORMAT, "key": digest, "num_chunks": self.num_chunks})
        self._chunks = self._root.require_group("chunks")

    def _existing_attrs(self):
        """The store's attributes ({} for a new store) once its root and its
        chunks folder are checked (_store_files.check_group)."""
        if not os.path.exists(self.path):
            return {}
        _files.check_group(self.path, self.path, ".", root=True)
        _files.check_group(os.path.join(self.path, "chunks"), self.path, "chunks")
        attrs = _files.read_json(os.path.join(self.path, ".zattrs"), _files.MAX_META_BYTES, self.path, ".zattrs")
        if attrs is None and os.path.lexists(os.path.join(self.path, ".zattrs")):
            raise ValueError(f"store {self.path!r}: .zattrs is not JSON")
        if attrs is not None and not isinstance(attrs, dict):
            raise ValueError(f"store {self.path!r}: .zattrs is not a JSON object")
        return attrs or {}

    def _chunk_attrs(self, name):
        """Chunk `name`'s attributes, or None when it has none yet; HostileStore
        when its folder or .zattrs is not what write() makes."""
        folder = os.path.join(self.path, "chunks", name)
        if not _files.real_directory(folder, self.path, f"chunks/{name}"):
            return None
        attrs = _files.read_json(os.path.join(folder, ".zattrs"), _files.MAX_ATTRS_BYTES, self.path,
                                 f"chunks/{name}/.zattrs")
        return attrs if isinstance(attrs, dict) else None

    def _checked_layout(self, name, attrs):
        """(fields, strings) of a complete chunk's attributes, as write() makes
        them; HostileStore otherwise (a field name could name another folder)."""
        fields, strings, digest = attrs.get("fields"), attrs.get("strings"), attrs.get("sha256")
        ok = isinstance(fields, list) and len(fields) <= _files.MAX_FIELDS and isinstance(digest, str) and \
            isinstance(attrs.get("key", ""), str) and \
            all(isinstance(f, str) and _files.plain_name(f) for f in fields) and len(set(fields)) == len(fields) and \
            isinstance(strings, dict) and len(strings) <= _files.MAX_FIELDS and \
            all(isinstance(v, list) and all(isinstance(x, str) for x in v) for v in strings.values())
        if not ok:
            raise _files.HostileStore(f"store {self.path!r}: chunks/{name}/.zattrs is not what ccma writes "
                                      "(fields, strings, sha256)")
        return fields, strings

    def done(self):
        """Indices of the chunks whose write completed (not yet hash-checked)."""
        out = set()
        try:
            names = os.listdir(os.path.join(self.path, "chunks"))
        except FileNotFoundError:
            return out
        for name in names:
            if name.isdigit() and 0 <= int(name) < self.num_chunks:
                attrs = self._chunk_attrs(name)
                if attrs is not None and attrs.get("complete") is True:
                    out.add(int(name))
        return out

    def read(self, index):
        """Chunk `index` as written, or None when it is missing, incomplete,
        corrupted or of another batch (that one with a UserWarning naming it);
        ValueError (naming the store and the array) when it holds what ccma
        never writes (see the module)."""
        name = str(int(index))
        attrs = self._chunk_attrs(name)
        if attrs is None or attrs.get("complete") is not True:
            return None
        fields, strings = self._checked_layout(name, attrs)
        folder = os.path.join(self.path, "chunks", name)
        metas = {}
        for field in fields:  # every array's metadata before any data
            what = f"chunks/{name}/{field}"
            if not _files.real_directory(os.path.join(folder, field), self.path, what):
                return None
            meta = _files.read_json(os.path.join(folder, field, ".zarray"), _files.MAX_META_BYTES, self.path,
                                    what + "/.zarray")
            if meta is None:
                return None
            metas[field] = _files.check_array_meta(meta, self.path, what)
        if attrs.get("key") != self._key:  # checked after what would make the store hostile
            warnings.warn(f"store {self.path!r}: chunks/{name} belongs to another batch (another map or sweep, or "
                          "an older ccma: its key is not this store's); computing it again", stacklevel=2)
            return None
        arrays = {}
        for field, (dtype, shape, compressed) in metas.items():
            arrays[field] = _files.read_array(os.path.join(folder, field), dtype, shape, compressed, self.path,
                                              f"chunks/{name}/{field}")
            if arrays[field] is None:
                return None
        if _digest(arrays, strings, self._key) != attrs["sha256"]:
            return None
        out = dict(arrays)
        out.update(strings)
        return out

    def _remove(self, name):
        """Deletes chunks/<name> whatever it is, never following a link: a
        planted link is removed, not written through."""
        folder = os.path.join(self.path, "chunks", name)
        if os.path.isdir(folder) and not os.path.islink(folder):
            shutil.rmtree(folder)  # unlinks the links inside, never their targets
        elif os.path.lexists(folder):
            os.unlink(folder)

    def write(self, index, result):
        """Writes chunk `index` (a dict of arrays and lists of str); the marker last."""
        name = str(int(index))
        self._remove(name)  # a half-written or corrupted earlier attempt
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
        group.attrs.update({"fields": sorted(arrays), "strings": strings, "key": self._key,
                            "sha256": _digest(arrays, strings, self._key)})
        group.attrs["complete"] = True
