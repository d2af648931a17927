"""Keep numba's on-disk cache of the simulator's kernels in step with their sources.

numba keys each cached function on the modification time of the file that defines it,
so a kernel in ``_integrators.py`` that inlines a function of ``_kernels.py`` keeps its
cached machine code after ``_kernels.py`` changes: doubling the Hertz constant in
``_kernels.py`` changed nothing until the cache was deleted by hand. Here every cache
folder of the ``ballpass.simulate`` package carries a stamp with the fingerprint of *all*
its sources; :func:`clear_stale_cache` runs before any kernel module is imported and
deletes the cached kernels of a folder whose stamp differs, so numba recompiles from the
current sources. An unchanged install keeps its cache (no recompilation).
"""

from __future__ import annotations

import hashlib
import os
from pathlib import Path

__all__ = ["source_fingerprint", "clear_stale_cache", "cache_dirs", "has_compiled_kernels"]

#: the package whose sources define the compiled kernels
PACKAGE_DIR = Path(__file__).resolve().parent
STAMP_NAME = "ballpass-kernels.sha256"


def source_fingerprint(package_dir: Path = PACKAGE_DIR) -> str:
    """SHA-256 (hex) of every ``.py`` source of the simulator package, path and bytes.

    Any edit of a kernel, an integrator or a model's parameters changes it: datasets
    store it to refuse resuming with a simulator that would produce other signals.

    Parameters
    ----------
    package_dir : Path, optional
        Package folder (default: ``ballpass/simulate``).

    Returns
    -------
    str
        64 hexadecimal digits.

    Examples
    --------
    >>> from ballpass.simulate import source_fingerprint
    >>> len(source_fingerprint())
    64
    """
    digest = hashlib.sha256()
    for path in sorted(package_dir.rglob("*.py")):
        digest.update(path.relative_to(package_dir).as_posix().encode())
        digest.update(b"\0")
        digest.update(path.read_bytes())
        digest.update(b"\0")
    return digest.hexdigest()


def cache_dirs(package_dir: Path = PACKAGE_DIR) -> list[Path]:
    """Folders where numba may keep cached kernels of the package: each source
    folder's ``__pycache__`` and, with ``NUMBA_CACHE_DIR`` set, its mirror there."""
    source_dirs = sorted({p.parent for p in package_dir.rglob("*.py")})
    dirs = [d / "__pycache__" for d in source_dirs]
    root = os.environ.get("NUMBA_CACHE_DIR")
    if root:
        # numba mirrors the absolute source folder below NUMBA_CACHE_DIR
        dirs += [Path(root) / d.relative_to(d.anchor) for d in source_dirs]
    return dirs


def clear_stale_cache(package_dir: Path = PACKAGE_DIR) -> list[Path]:
    """Delete cached kernels (``*.nbi``, ``*.nbc``) compiled from other sources.

    Parameters
    ----------
    package_dir : Path, optional
        Package folder (default: ``ballpass/simulate``).

    Returns
    -------
    list of Path
        The files deleted (empty when every cache was current).
    """
    fingerprint = source_fingerprint(package_dir)
    deleted: list[Path] = []
    for folder in cache_dirs(package_dir):
        stamp = folder / STAMP_NAME
        try:
            if stamp.read_text() == fingerprint:
                continue
        except OSError:
            pass  # no stamp yet: whatever is cached there is of unknown origin
        try:
            # stamp a folder before numba fills it, or its first kernels would count as
            # of unknown origin on the next import and be compiled twice
            folder.mkdir(parents=True, exist_ok=True)
        except OSError:
            continue
        for pattern in ("*.nbi", "*.nbc"):
            for path in folder.glob(pattern):
                try:
                    path.unlink()
                    deleted.append(path)
                except FileNotFoundError:
                    pass  # another process cleared it first
                except OSError:
                    break  # read-only cache folder: numba falls back to its own locator
        try:
            tmp = folder / f".{STAMP_NAME}.{os.getpid()}"
            tmp.write_text(fingerprint)
            os.replace(tmp, stamp)
        except OSError:
            pass
    return deleted


def has_compiled_kernels(package_dir: Path = PACKAGE_DIR) -> bool:
    """Whether numba's on-disk cache holds any compiled kernel of the package.

    ``False`` on a fresh install, after an update (:func:`clear_stale_cache` removed the
    kernels of other sources) or with an empty ``NUMBA_CACHE_DIR``: the next simulation
    compiles its kernels first, which takes tens of seconds once.

    Parameters
    ----------
    package_dir : Path, optional
        Package folder (default: ``ballpass/simulate``).

    Returns
    -------
    bool
    """
    folders = cache_dirs(package_dir)
    root = os.environ.get("NUMBA_CACHE_DIR")
    if root:   # numba's locator of a user-given folder comes first: it reads only there
        folders = [f for f in folders if Path(root) in f.parents]
    return any(any(folder.glob("*.nbi")) for folder in folders if folder.is_dir())
