"""Downloads into the cache, against a local HTTP server on the loopback address only."""

import hashlib
import http.server
import io
import threading
import zipfile
from functools import partial

import numpy as np
import pytest
import scipy.io

from ballpass import datasets
from ballpass.datasets import download as fetch_module


class _Handler(http.server.SimpleHTTPRequestHandler):
    requests: list = []
    truncate: set = set()

    def log_message(self, *args):  # keep the test output clean
        pass

    def do_GET(self):  # noqa: N802 - the http.server interface
        type(self).requests.append(self.path)
        name = self.path.lstrip("/")
        if name in type(self).truncate:  # announce more bytes than are sent
            body = (self.directory_path / name).read_bytes()
            self.send_response(200)
            self.send_header("Content-Length", str(len(body) + 100))
            self.end_headers()
            self.wfile.write(body)
            return
        super().do_GET()


@pytest.fixture
def server(tmp_path):
    """An HTTP server on 127.0.0.1 serving ``tmp_path / "remote"``; yields (base url,
    remote folder, handler class)."""
    remote = tmp_path / "remote"
    remote.mkdir()
    handler = type("Handler", (_Handler,), {"requests": [], "truncate": set(),
                                            "directory_path": remote})
    httpd = http.server.ThreadingHTTPServer(("127.0.0.1", 0), partial(handler, directory=remote))
    thread = threading.Thread(target=httpd.serve_forever, daemon=True)
    thread.start()
    try:
        yield f"http://127.0.0.1:{httpd.server_address[1]}", remote, handler
    finally:
        httpd.shutdown()
        httpd.server_close()


def _cwru_file(path, record, n=24_000):
    rng = np.random.default_rng(record)
    scipy.io.savemat(path, {f"X{record:03d}_DE_time": rng.standard_normal((n, 1)),
                            f"X{record:03d}_FE_time": rng.standard_normal((n, 1)),
                            f"X{record:03d}RPM": np.array([[1797.0]])})


def test_fetch_downloads_once_and_checks_the_hash(server, tmp_path):
    base, remote, handler = server
    (remote / "a.bin").write_bytes(b"vibration" * 1000)
    cache = tmp_path / "cache"
    digest = hashlib.sha256(b"vibration" * 1000).hexdigest()
    path = datasets.fetch(f"{base}/a.bin", sha256=digest, cache_dir=cache, progress=False)
    assert path.read_bytes() == b"vibration" * 1000 and path.parent == cache
    assert datasets.fetch(f"{base}/a.bin", cache_dir=cache, progress=False) == path
    assert handler.requests == ["/a.bin"]  # the second call read the cache
    # a wrong hash: the download is refused and nothing stays in the cache
    with pytest.raises(ValueError, match="expected 0{64}"):
        datasets.fetch(f"{base}/a.bin", sha256="0" * 64, filename="b.bin", cache_dir=cache,
                       progress=False)
    assert sorted(p.name for p in cache.iterdir()) == ["a.bin", "sha256.json"]


def test_an_altered_cached_file_is_fetched_again(server, tmp_path):
    base, remote, handler = server
    (remote / "a.bin").write_bytes(b"x" * 5000)
    cache = tmp_path / "cache"
    path = datasets.fetch(f"{base}/a.bin", cache_dir=cache, progress=False)  # hash recorded
    path.write_bytes(b"x" * 10)  # truncated on disk since
    assert datasets.fetch(f"{base}/a.bin", cache_dir=cache, progress=False).read_bytes() == (
        b"x" * 5000)
    assert handler.requests == ["/a.bin", "/a.bin"]


def test_a_broken_transfer_leaves_nothing(server, tmp_path):
    base, remote, handler = server
    (remote / "a.bin").write_bytes(b"x" * 5000)
    handler.truncate.add("a.bin")
    cache = tmp_path / "cache"
    with pytest.raises(OSError, match="ended after 5000 of 5100 bytes"):
        datasets.fetch(f"{base}/a.bin", cache_dir=cache, progress=False)
    assert list(cache.iterdir()) == []


@pytest.mark.parametrize(("kwargs", "match"), [
    ({"url": "file:///etc/passwd"}, "^url must be an http"),
    ({"url": "http://127.0.0.1:9/x", "filename": "../x"}, "^filename must be a plain"),
    ({"url": "http://127.0.0.1:9/x", "sha256": "abc"}, "^sha256 must be 64"),
])
def test_bad_arguments_are_refused_before_any_request(kwargs, match, tmp_path):
    url = kwargs.pop("url")
    with pytest.raises(ValueError, match=match):
        datasets.fetch(url, cache_dir=tmp_path, progress=False, **kwargs)


def test_fetch_cwru_checks_the_record_and_feeds_the_loader(server, tmp_path):
    base, remote, handler = server
    _cwru_file(remote / "105.mat", 105)
    _cwru_file(remote / "118.mat", 130)  # a mirror serving the wrong record under 118
    cache = tmp_path / "cache"
    (path,) = datasets.fetch_cwru([105], cache_dir=cache, url=base + "/{record}.mat",
                                  progress=False)
    X, meta = datasets.load_cwru([path])
    # record 105: 12 kHz drive end, inner race 0.007 in, 0 hp (the data centre's table)
    assert set(meta["label"]) == {"inner"} and X.shape[1] == 12_000
    with pytest.raises(ValueError, match="does not hold CWRU record 118"):
        datasets.fetch_cwru(118, cache_dir=cache, url=base + "/{record}.mat", progress=False)
    assert not (cache / "118.mat").exists()
    with pytest.raises(ValueError, match=r"unknown: \[157\]"):
        datasets.fetch_cwru([157], cache_dir=cache, url=base + "/{record}.mat")
    assert handler.requests == ["/105.mat", "/118.mat"]


def test_fetch_mfpt_unpacks_and_refuses_members_outside_its_folder(server, tmp_path):
    base, remote, handler = server
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w") as zf:
        zf.writestr("MFPT Fault Data Sets/1 - Three Baseline Conditions/baseline_1.mat", b"m")
    (remote / "mfpt.zip").write_bytes(buf.getvalue())
    cache = tmp_path / "cache"
    folder = datasets.fetch_mfpt(cache_dir=cache, url=f"{base}/mfpt.zip", progress=False)
    assert [p.name for p in folder.rglob("*.mat")] == ["baseline_1.mat"]
    # a tampered archive: a member that climbs out of the folder is refused, nothing written
    canary = tmp_path / "canary.mat"
    canary.write_bytes(b"keep")
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w") as zf:
        zf.writestr("a.mat", b"m")
        zf.writestr("../../canary.mat", b"overwritten")
    (remote / "evil.zip").write_bytes(buf.getvalue())
    with pytest.raises(ValueError, match="members outside its folder"):
        datasets.fetch_mfpt(cache_dir=cache, url=f"{base}/evil.zip", progress=False)
    assert canary.read_bytes() == b"keep" and not (cache / "evil").exists()


def test_cache_folder_follows_the_environment(monkeypatch, tmp_path):
    monkeypatch.setenv("BALLPASS_DATA", str(tmp_path / "data"))
    assert fetch_module.cache_folder() == tmp_path / "data"
    monkeypatch.delenv("BALLPASS_DATA")
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    assert fetch_module.cache_folder() == tmp_path / "xdg" / "ballpass"
