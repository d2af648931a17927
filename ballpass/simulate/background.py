"""The rest of the machine in a simulated measurement: coloured background noise and
shaft-rate lines, added to every model's output by :func:`._shared.add_noise`.

A bearing is never alone on a machine: unbalance and misalignment put lines at the
shaft rate and its harmonics into every accelerometer signal (a healthy CWRU fan-end
channel carries a 4x line 25-29 times above its background), and the background of a
machine falls with frequency rather than being white.
"""

from __future__ import annotations

import numpy as np

from ..scene import Scene

__all__ = ["coloured_noise", "shaft_lines"]


def coloured_noise(rng: np.random.Generator, shape: tuple, fs: float,
                   slope_db_oct: float) -> np.ndarray:
    """Gaussian noise of unit RMS whose power spectrum falls (or rises) by
    ``slope_db_oct`` dB per octave; exactly ``rng.standard_normal(shape)`` for 0.

    White noise shaped in the frequency domain by |H(f)| = (f / f_ref)^(slope / 20 /
    log10(2)), with the DC bin set to zero and the lowest bin's gain used below it,
    then scaled to unit RMS per row.

    Parameters
    ----------
    rng : numpy.random.Generator
    shape : tuple
        (n_rows, n_samples).
    fs : float
        Sampling rate, Hz.
    slope_db_oct : float
        dB per octave: 0 white, -3 pink, -6 brown.

    Returns
    -------
    ndarray of ``shape``

    Examples
    --------
    >>> import numpy as np
    >>> x = coloured_noise(np.random.default_rng(0), (1, 4096), 12_000.0, -3.0)
    >>> round(float(np.sqrt(np.mean(x**2))), 6)
    1.0
    """
    white = rng.standard_normal(shape)
    if slope_db_oct == 0.0:
        return white
    n = shape[-1]
    f = np.fft.rfftfreq(n, 1.0 / fs)
    gain = np.ones_like(f)
    if n > 1:
        f_pos = np.maximum(f, f[1])
        gain = (f_pos / f[1]) ** (slope_db_oct / (20.0 * np.log10(2.0)))
        gain[0] = 0.0
    x = np.fft.irfft(np.fft.rfft(white, axis=-1) * gain, n=n, axis=-1)
    rms = np.sqrt(np.mean(x**2, axis=-1, keepdims=True))
    return x / np.where(rms > 0.0, rms, 1.0)


def shaft_lines(scene: Scene, n_samples: int) -> np.ndarray:
    """The scene's shaft-rate lines sum_k a_k cos(k theta(t) + phi_k), m/s^2, shape
    (n_samples,); theta is the shaft angle (speed ramps included) and the phases phi_k
    come from the third child of ``SeedSequence(scene.seed)``.

    Examples
    --------
    >>> import ballpass as bp
    >>> s = bp.Scene("6205", rpm=1800, fs=12_000, resonance_hz=3500, shaft_harmonics=(0.0, 0.5))
    >>> x = shaft_lines(s, s.n_samples)
    >>> round(float(abs(np.fft.rfft(x))[60] * 2 / s.n_samples), 3)   # 2x = 60 Hz
    0.5
    """
    amps = np.asarray(scene.shaft_harmonics, dtype=float)
    if amps.size == 0:
        return np.zeros(n_samples)
    seed = np.random.SeedSequence(scene.seed).spawn(3)[2]
    phases = np.random.default_rng(seed).uniform(0.0, 2.0 * np.pi, amps.size)
    theta = scene.speed.shaft_angle(np.arange(n_samples) / scene.fs, scene.duration_s)
    k = np.arange(1, amps.size + 1)
    return (amps[:, None] * np.cos(k[:, None] * theta[None, :] + phases[:, None])).sum(axis=0)
