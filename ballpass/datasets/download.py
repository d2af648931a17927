"""Download public bearing recordings into a local cache, checked, atomically.

:func:`fetch` is the general tool (in the manner of ``pooch``): a file is downloaded
once into a cache folder, streamed through SHA-256, written under a temporary name and
renamed, so an interrupted download never leaves a file that looks complete. A hash
given by the caller is checked; without one the hash of the first download is recorded
beside the files (``sha256.json``) and every later use checks the file against it, so a
cached file that was altered or truncated is noticed and fetched again.

:func:`fetch_cwru` and :func:`fetch_mfpt` know where the Case Western Reserve
University and MFPT recordings live. Neither source publishes checksums, so a download
is also checked by its content: a CWRU file must hold its record's variables
(``X105_DE_time`` in ``105.mat``), and the MFPT archive must hold ``.mat`` files.
What they return goes straight into :func:`ballpass.datasets.load_cwru` and
:func:`ballpass.datasets.load_mfpt`.

The cache folder is ``cache_dir`` when given, else the ``BALLPASS_DATA`` environment
variable, else ``$XDG_CACHE_HOME/ballpass`` (``~/.cache/ballpass``).
"""

from __future__ import annotations

import hashlib
import json
import os
import re
import shutil
import urllib.parse
import urllib.request
import zipfile
from pathlib import Path

__all__ = ["cache_folder", "fetch", "fetch_cwru", "fetch_mfpt", "CWRU_URL", "MFPT_URL"]

#: Where the CWRU Bearing Data Center serves a record by its number.
CWRU_URL = "https://engineering.case.edu/sites/default/files/{record}.mat"
#: The MFPT Society's archive of its bearing fault data sets (2020 edition).
MFPT_URL = (
    "https://www.mfpt.org/wp-content/uploads/2020/02/"
    "MFPT-Fault-Data-Sets-20200227T131140Z-001.zip"
)
_REGISTRY = "sha256.json"
_CHUNK = 1 << 20
_PLAIN_NAME = re.compile(r"^[A-Za-z0-9][A-Za-z0-9._@+-]*$")


def cache_folder(cache_dir=None) -> Path:
    """The folder downloads go to (created when missing).

    Parameters
    ----------
    cache_dir : str or os.PathLike, optional
        Folder to use. Default: ``$BALLPASS_DATA``, else ``$XDG_CACHE_HOME/ballpass``,
        else ``~/.cache/ballpass``.

    Returns
    -------
    Path

    Examples
    --------
    >>> import tempfile
    >>> from ballpass.datasets.download import cache_folder
    >>> cache_folder(tempfile.mkdtemp()).is_dir()
    True
    """
    if cache_dir is None:
        cache_dir = os.environ.get("BALLPASS_DATA") or (
            Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache") / "ballpass"
        )
    folder = Path(cache_dir).expanduser()
    folder.mkdir(parents=True, exist_ok=True)
    return folder


def _file_sha256(path: Path) -> str:
    digest = hashlib.sha256()
    with open(path, "rb") as f:
        while chunk := f.read(_CHUNK):
            digest.update(chunk)
    return digest.hexdigest()


def _read_registry(folder: Path) -> dict:
    try:
        return json.loads((folder / _REGISTRY).read_text())
    except (OSError, ValueError):
        return {}


def _record_hash(folder: Path, name: str, sha256: str) -> None:
    registry = _read_registry(folder)
    registry[name] = sha256
    tmp = folder / f".{_REGISTRY}.{os.getpid()}"
    tmp.write_text(json.dumps(registry, indent=1, sort_keys=True))
    os.replace(tmp, folder / _REGISTRY)


def _check_sha256(sha256) -> str | None:
    if sha256 is None:
        return None
    if not (isinstance(sha256, str) and re.fullmatch(r"[0-9a-fA-F]{64}", sha256)):
        raise ValueError(f"sha256 must be 64 hexadecimal digits, got {sha256!r}")
    return sha256.lower()


def _download(url: str, target: Path, timeout: float, progress: bool) -> str:
    """Stream ``url`` into ``target`` (a temporary name); return its SHA-256."""
    digest = hashlib.sha256()
    request = urllib.request.Request(url, headers={"User-Agent": "ballpass"})
    with urllib.request.urlopen(request, timeout=timeout) as response, open(target, "wb") as out:
        total = response.headers.get("Content-Length")
        bar = None
        if progress:
            from tqdm.auto import tqdm

            bar = tqdm(total=int(total) if total else None, unit="B", unit_scale=True,
                       desc=target.name.split(".part")[0].lstrip("."), leave=False)
        try:
            while chunk := response.read(_CHUNK):
                digest.update(chunk)
                out.write(chunk)
                if bar is not None:
                    bar.update(len(chunk))
        finally:
            if bar is not None:
                bar.close()
        if total is not None and out.tell() != int(total):
            raise OSError(f"download of {url} ended after {out.tell()} of {total} bytes")
    return digest.hexdigest()


def fetch(url: str, *, sha256: str | None = None, filename: str | None = None,
          cache_dir=None, timeout: float = 60.0, progress: bool = True) -> Path:
    """Download ``url`` into the cache once and return the local path.

    Parameters
    ----------
    url : str
        ``http://`` or ``https://`` address of the file.
    sha256 : str, optional
        Expected SHA-256 (64 hex digits). A download that does not match is deleted and
        raises; a cached file that does not match is fetched again.
    filename : str, optional
        Name in the cache (default: the last part of the URL's path). A plain name: no
        folders, no ``..``.
    cache_dir : str or os.PathLike, optional
        See :func:`cache_folder`.
    timeout : float, optional
        Seconds to wait for the server (default 60).
    progress : bool, optional
        Show a progress bar while downloading (default True).

    Returns
    -------
    Path
        The cached file.

    Raises
    ------
    ValueError
        Bad ``url``, ``sha256`` or ``filename`` (before any download), or a download
        whose SHA-256 differs from ``sha256``.
    OSError
        The server could not be reached or the transfer broke off (nothing is left in
        the cache).

    Examples
    --------
    >>> import tempfile
    >>> from ballpass.datasets.download import fetch
    >>> fetch("ftp://example.org/x.mat", cache_dir=tempfile.mkdtemp())
    Traceback (most recent call last):
    ...
    ValueError: url must be an http:// or https:// address, got 'ftp://example.org/x.mat'
    """
    if not isinstance(url, str) or urllib.parse.urlsplit(url).scheme not in ("http", "https"):
        raise ValueError(f"url must be an http:// or https:// address, got {url!r}")
    sha256 = _check_sha256(sha256)
    name = filename if filename is not None else Path(urllib.parse.urlsplit(url).path).name
    if not (isinstance(name, str) and _PLAIN_NAME.match(name)):
        raise ValueError(
            f"filename must be a plain file name (letters, digits, . _ @ + -), got {name!r}"
        )
    folder = cache_folder(cache_dir)
    path = folder / name
    expected = sha256 or _read_registry(folder).get(name)
    if path.is_file():
        if expected is None or _file_sha256(path) == expected:
            if expected is None:
                _record_hash(folder, name, _file_sha256(path))
            return path
        path.unlink()  # altered or truncated since it was fetched: fetch it again
    part = folder / f".{name}.part{os.getpid()}"
    try:
        got = _download(url, part, timeout, progress)
        if sha256 is not None and got != sha256:
            raise ValueError(f"download of {url} has SHA-256 {got}, expected {sha256}")
        os.replace(part, path)
    finally:
        part.unlink(missing_ok=True)
    _record_hash(folder, name, got)
    return path


def fetch_cwru(records, *, cache_dir=None, url: str = CWRU_URL, progress: bool = True,
               timeout: float = 60.0) -> list[Path]:
    """Download CWRU Bearing Data Center records by number (``105`` is ``105.mat``).

    Each file is checked to hold its record's variables (``X105_DE_time`` ...); the
    numbers and what they stand for are the data centre's (see
    :func:`ballpass.datasets.load_cwru`, which reads the files by their numbers).

    Parameters
    ----------
    records : int or iterable of int
        Record numbers, e.g. ``97`` (healthy, 0 hp, 48 kHz), ``105`` (12 kHz drive end,
        inner race 0.007 in, 0 hp).
    cache_dir : str or os.PathLike, optional
        See :func:`cache_folder`.
    url : str, optional
        Address pattern with ``{record}`` (default :data:`CWRU_URL`; a mirror's pattern
        works as well).
    progress : bool, optional
        Show a progress bar per file (default True).
    timeout : float, optional
        Seconds to wait for the server (default 60).

    Returns
    -------
    list of Path
        The cached files, in the order asked.

    Raises
    ------
    ValueError
        A number the data centre does not have (before any download), or a file that
        does not hold its record (deleted from the cache).

    Examples
    --------
    >>> from ballpass.datasets.download import fetch_cwru
    >>> fetch_cwru([105, 157])
    Traceback (most recent call last):
    ...
    ValueError: records must be CWRU record numbers (97-100, 105-3008 with gaps); unknown: [157]

    With a network: ``load_cwru(fetch_cwru([97, 105, 118, 130]))``.
    """
    import scipy.io

    from ._cwru_table import RECORDS

    numbers = [records] if isinstance(records, int) else list(records)
    unknown = [n for n in numbers if isinstance(n, bool) or n not in RECORDS]
    if unknown or not numbers:
        raise ValueError(
            "records must be CWRU record numbers (97-100, 105-3008 with gaps); "
            f"unknown: {unknown or numbers}"
        )
    if "{record}" not in url:
        raise ValueError(f"url must contain '{{record}}', got {url!r}")
    paths = []
    for number in numbers:
        path = fetch(url.format(record=number), filename=f"{number}.mat", cache_dir=cache_dir,
                     timeout=timeout, progress=progress)
        try:
            names = [name for name, *_ in scipy.io.whosmat(path)]
        except Exception as err:  # noqa: BLE001 - any unreadable file is refused the same way
            names, reason = [], f"not a MATLAB file ({err})"
        else:
            reason = f"its variables are {names}"
        if not any(name.startswith(f"X{number:03d}_") for name in names):
            path.unlink(missing_ok=True)
            raise ValueError(
                f"{url.format(record=number)} does not hold CWRU record {number}: {reason}"
            )
        paths.append(path)
    return paths


def fetch_mfpt(*, cache_dir=None, url: str = MFPT_URL, sha256: str | None = None,
               progress: bool = True, timeout: float = 120.0) -> Path:
    """Download and unpack the MFPT bearing fault data sets; return their folder.

    Parameters
    ----------
    cache_dir : str or os.PathLike, optional
        See :func:`cache_folder`.
    url : str, optional
        The archive's address (default :data:`MFPT_URL`).
    sha256 : str, optional
        Expected SHA-256 of the archive.
    progress : bool, optional
        Show a progress bar (default True).
    timeout : float, optional
        Seconds to wait for the server (default 120).

    Returns
    -------
    Path
        Folder holding the unpacked ``.mat`` files (its sub-folders as in the
        archive), ready for :func:`ballpass.datasets.load_mfpt` (pass the files).

    Raises
    ------
    ValueError
        The archive holds no ``.mat`` file, or a member whose name would leave the
        folder (absolute, or with ``..``); nothing of it is unpacked then.
    """
    archive = fetch(url, sha256=sha256, cache_dir=cache_dir, progress=progress,
                    timeout=timeout)
    target = archive.with_suffix("")
    if target.is_dir() and any(target.rglob("*.mat")):
        return target
    with zipfile.ZipFile(archive) as zf:
        members = [m for m in zf.infolist() if not m.is_dir()]
        unsafe = [m.filename for m in members
                  if Path(m.filename).is_absolute() or ".." in Path(m.filename).parts]
        if unsafe:
            raise ValueError(f"{archive} has members outside its folder: {unsafe[:3]}")
        if not any(m.filename.lower().endswith(".mat") for m in members):
            raise ValueError(f"{archive} holds no .mat file")
        staging = target.with_name(f".{target.name}.unpack{os.getpid()}")
        shutil.rmtree(staging, ignore_errors=True)
        try:
            zf.extractall(staging, members)
            shutil.rmtree(target, ignore_errors=True)
            os.replace(staging, target)
        finally:
            shutil.rmtree(staging, ignore_errors=True)
    return target
