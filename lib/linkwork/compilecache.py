"""The compile cache: one folder (``LINKWORK_CACHE``, else ~/.cache/linkwork) for the generated scene modules and for
numba's compiled code of every cached function, so that nothing is written below lib/.  The compiled code of this
package's own functions is filed under its source's content, not its folder's path: every copy of lib (a clone, a test's
or a benchmark's copy) shares what another compiled from the same source.

A cache entry that cannot be read (a truncated or corrupted ``.nbi``/``.nbc`` file) is compiled again and
overwritten, with one line on stderr naming it; a cache folder that cannot be used is named before any job
(``problem``, called by the Snakefile's validation).  Standard library only until numba is asked for.
"""

from __future__ import annotations

import fcntl
import hashlib
import os
import sys
from functools import lru_cache
from pathlib import Path

#: What reading a damaged cache entry may raise: anything (pickle turns random bytes into any error, MemoryError
#: included); an entry that cannot be read is compiled again.
UNREADABLE = (Exception,)


def root() -> Path:
    """The compile cache folder: $LINKWORK_CACHE, else ~/.cache/linkwork."""
    return Path(os.environ.get("LINKWORK_CACHE") or Path.home() / ".cache" / "linkwork")


#: The compile cache's own folders: numba's compiled functions, the generated scene modules, the compile locks.
SUBFOLDERS = ("numba", "multibody", "locks")


def problem() -> str | None:
    """Why the compile cache folder cannot be used (a file in its place, no write permission), or None."""
    folder = root()
    named = f"LINKWORK_CACHE={folder}" if os.environ.get("LINKWORK_CACHE") else f"the compile cache {folder}"
    if folder.exists() and not folder.is_dir():
        return f"{named} is a file, not a folder: point LINKWORK_CACHE to a folder (or unset it for ~/.cache/linkwork)"
    for part in SUBFOLDERS:  # the folders the jobs compile and lock in
        if (folder / part).exists() and not (folder / part).is_dir():
            return f"{folder / part} is a file where the compile cache keeps a folder: remove it (rm {folder / part})"
    existing = folder
    while not existing.exists() and existing != existing.parent:
        existing = existing.parent
    if not os.access(existing, os.W_OK | os.X_OK):
        return f"{named} cannot be written ({existing} is not writable): point LINKWORK_CACHE to a folder you can write"
    return None


_SAID: set[str] = set()


def _said(path: str, exc: BaseException) -> None:
    if path in _SAID:  # numba reads the index again before it writes the entry anew
        return
    _SAID.add(path)
    print(
        f"linkwork: compile cache entry {path} was unreadable ({type(exc).__name__}); compiling it again",
        file=sys.stderr, flush=True,
    )


def use_for_numba() -> None:
    """numba's cache of every ``cache=True`` function goes to <root>/numba (unless NUMBA_CACHE_DIR says where), and an
    unreadable entry is a cache miss (compiled again, then overwritten) instead of an error.  Call it before the
    decorated functions are defined."""
    from numba.core import caching, config

    if not os.environ.get("NUMBA_CACHE_DIR"):
        config.CACHE_DIR = str(root() / "numba")
    files = caching.IndexDataCacheFile
    if getattr(files, "_linkwork_tolerant", False):
        return
    load_index, load_data = files._load_index, files._load_data

    def _load_index(self):
        try:
            return load_index(self)
        except UNREADABLE as exc:
            _said(self._index_path, exc)
            return {}

    def _load_data(self, name):
        try:
            return load_data(self, name)
        except UNREADABLE as exc:
            _said(self._data_path(name), exc)
            raise OSError(str(exc)) from exc  # IndexDataCacheFile.load reads an OSError as a miss

    files._load_index, files._load_data, files._linkwork_tolerant = _load_index, _load_data, True
    _file_by_content(caching)


#: This package's folder: the sources whose compiled code is filed by content.
PACKAGE = Path(__file__).resolve().parent


@lru_cache(maxsize=None)
def content_subpath(py_file: str) -> str:
    """The cache sub-folder of a source file: its name and a digest of its bytes (numba's default names it after the
    path of the file's folder, so that a copy of the same source elsewhere compiles everything again).  numba's index
    still checks each entry against the source's own content hash."""
    path = Path(py_file)
    return f"{path.stem}_{hashlib.sha256(path.read_bytes()).hexdigest()[:20]}"


def _file_by_content(caching) -> None:
    """Put a locator that files this package's functions by content (``content_subpath``) before numba's own; every
    other source (the generated scene modules included) keeps numba's default."""
    impl = caching.CacheImpl
    if any(getattr(c, "_linkwork", False) for c in impl._locator_classes):
        return

    class ByContent(caching.UserProvidedCacheLocator):
        _linkwork = True

        @classmethod
        def get_suitable_cache_subpath(cls, py_file):
            return content_subpath(str(py_file))

        @classmethod
        def from_function(cls, py_func, py_file):
            if not Path(py_file).resolve().is_relative_to(PACKAGE):
                return None
            return super().from_function(py_func, py_file)

    impl._locator_classes.insert(0, ByContent)


def compile_once(dispatcher, signature: tuple, name: str) -> None:
    """Compile a numba dispatcher for ``signature`` (argument types), or load it from the cache, one process at a
    time: a process that finds another compiling the same function (``name``) waits for it, then loads the result
    from the cache instead of compiling it again (two jobs started together used to compile the same scene twice).
    Once compiled in this process, nothing is locked."""
    if signature in dispatcher.overloads:
        return
    folder = root() / "locks"
    folder.mkdir(parents=True, exist_ok=True)
    with open(folder / f"{name}.lock", "a") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        try:
            dispatcher.compile(signature)
        finally:
            fcntl.flock(lock, fcntl.LOCK_UN)
