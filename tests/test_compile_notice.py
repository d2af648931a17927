"""The first simulation with an empty kernel cache says it is compiling."""

import logging

import pytest

import ballpass as bp
from ballpass.simulate import _cache

sim = bp.simulate  # the callable subpackage


@pytest.fixture
def fresh_process(monkeypatch):
    """Pretend this process has not yet looked for compiled kernels."""
    monkeypatch.setattr(sim, "_compile_checked", False)


def _scene():
    return bp.Scene(bearing="6205", rpm=1797, fault=bp.Fault("outer"), duration_s=0.02,
                    fs=48_000)


def test_empty_cache_is_announced_once(fresh_process, monkeypatch, tmp_path, caplog):
    # an empty cache folder: no kernel compiled yet
    monkeypatch.setattr(_cache, "cache_dirs", lambda package_dir=None: [tmp_path])
    with caplog.at_level(logging.INFO, logger="ballpass"):
        sim.simulate(_scene())
        sim.simulate(_scene())
    warnings = [r for r in caplog.records if r.levelno == logging.WARNING]
    # once per process, before the work, and the time of that first run afterwards
    assert len(warnings) == 1 and "compiling" in warnings[0].getMessage()
    assert any("took" in r.getMessage() for r in caplog.records if r.levelno == logging.INFO)


def test_cached_kernels_are_not_announced(fresh_process, monkeypatch, tmp_path, caplog):
    (tmp_path / "_integrators.rk4-10.py311.nbi").write_bytes(b"")
    monkeypatch.setattr(_cache, "cache_dirs", lambda package_dir=None: [tmp_path])
    with caplog.at_level(logging.INFO, logger="ballpass"):
        sim.simulate(_scene())
    assert not [r for r in caplog.records if "compil" in r.getMessage()]


def test_has_compiled_kernels_reads_the_cache_folders(monkeypatch, tmp_path):
    monkeypatch.setattr(_cache, "cache_dirs", lambda package_dir=None: [tmp_path / "none"])
    assert not _cache.has_compiled_kernels()
    monkeypatch.setattr(_cache, "cache_dirs", lambda package_dir=None: [tmp_path])
    (tmp_path / "k.nbc").write_bytes(b"")  # data without an index is no usable kernel
    assert not _cache.has_compiled_kernels()
    (tmp_path / "k.nbi").write_bytes(b"")
    assert _cache.has_compiled_kernels()


def test_a_user_cache_folder_is_the_only_one_numba_reads(monkeypatch, tmp_path):
    """With ``NUMBA_CACHE_DIR`` set numba reads its kernels there only, so kernels left in
    the package's ``__pycache__`` do not count: an empty user folder means a compile is
    coming and its notice is due (planted: counting ``__pycache__`` too; fails)."""
    package = tmp_path / "pkg"
    (package / "__pycache__").mkdir(parents=True)
    (package / "kernels.py").write_text("")
    (package / "__pycache__" / "kernels.f-1.py311.nbi").write_bytes(b"")
    monkeypatch.delenv("NUMBA_CACHE_DIR", raising=False)
    assert _cache.has_compiled_kernels(package)
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path / "user"))
    assert not _cache.has_compiled_kernels(package)
    mirror = tmp_path / "user" / package.relative_to(package.anchor)
    mirror.mkdir(parents=True)
    (mirror / "kernels.f-1.py311.nbi").write_bytes(b"")
    assert _cache.has_compiled_kernels(package)
