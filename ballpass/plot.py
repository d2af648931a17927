"""Figures of vibration signals: waveform, envelope spectrum with fault markers, kurtogram.

Every plotting function takes ``ax=None`` (a new figure when omitted) and returns the
Axes it drew on; nothing calls ``plt.show()``. matplotlib is imported on first use;
without a display (no ``DISPLAY``/``WAYLAND_DISPLAY`` on Linux and no ``MPLBACKEND``)
the non-interactive Agg backend is selected, so figures can be saved on servers.
:func:`signal_overview` builds its figure without pyplot (no global state), which
suits command-line tools and loops.

Examples
--------
>>> import numpy as np
>>> import ballpass as bp
>>> from ballpass import plot
>>> fs = 12_000.0
>>> x = np.random.default_rng(0).standard_normal(12_000)
>>> f, ses = bp.features.envelope_spectrum(x, fs, band=(2000, 4000))
>>> freqs = bp.Bearing.catalog("6205").frequencies(29.95)
>>> ax = plot.envelope_spectrum(f, ses, frequencies=freqs)
>>> ax.get_xlabel()
'Frequency (Hz)'
"""

from __future__ import annotations

import numbers
import os
import sys
from pathlib import Path

import numpy as np

__all__ = [
    "waveform",
    "spectrum",
    "psd",
    "spectrogram",
    "envelope_spectrum",
    "kurtogram",
    "signal_overview",
]

#: Marker style per fault line: (label, colour).
LINE_STYLE = {
    "shaft": ("shaft", "0.55"),
    "ftf": ("FTF", "tab:purple"),
    "bpfo": ("BPFO", "tab:red"),
    "bpfi": ("BPFI", "tab:blue"),
    "bsf": ("BSF", "tab:olive"),
    "ball_defect": ("2×BSF", "tab:green"),
}
#: Lines marked by default (BSF itself is rarely seen; a ball defect shows at 2×BSF).
DEFAULT_LINES = ("shaft", "ftf", "bpfo", "bpfi", "ball_defect")


def _pyplot():
    """Import pyplot, selecting Agg when there is no display to draw on."""
    import matplotlib

    headless = sys.platform.startswith("linux") and not (
        os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY")
    )
    if headless and "matplotlib.pyplot" not in sys.modules and not os.environ.get("MPLBACKEND"):
        matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _axes(ax):
    if ax is not None:
        return ax
    _, ax = _pyplot().subplots(figsize=(8, 3.5), layout="constrained")
    return ax


def waveform(x, fs_or_t, *, channels=None, unit="m/s²", ax=None):
    """Plot signal(s) against time.

    Parameters
    ----------
    x : array_like, shape (n_samples,) or (n_channels, n_samples)
        Signal(s).
    fs_or_t : float or array_like of shape (n_samples,)
        Sampling frequency in Hz, or the sample times in s.
    channels : sequence of str, optional
        Channel names for the legend (default ``ch0, ch1, ...``; no legend for one).
    unit : str, optional
        Unit for the y label (default ``"m/s²"``).
    ax : matplotlib.axes.Axes, optional
        Axes to draw on (default: a new figure).

    Returns
    -------
    matplotlib.axes.Axes

    Examples
    --------
    >>> import numpy as np
    >>> from ballpass.plot import waveform
    >>> ax = waveform(np.sin(np.arange(1000) / 10), 1000.0)
    >>> ax.get_xlabel()
    'Time (s)'
    """
    data = np.atleast_2d(np.asarray(x, dtype=float))
    if data.ndim != 2 or data.shape[-1] < 1:
        raise ValueError(
            f"x must have shape (n_samples,) or (n_channels, n_samples), got {data.shape}"
        )
    n = data.shape[-1]
    if np.ndim(fs_or_t) == 0:
        if not (np.isfinite(fs_or_t) and fs_or_t > 0):
            raise ValueError(
                f"fs_or_t must be a sampling frequency > 0 Hz or times, got {fs_or_t!r}"
            )
        t = np.arange(n) / float(fs_or_t)
    else:
        t = np.asarray(fs_or_t, dtype=float)
        if t.shape != (n,):
            raise ValueError(f"fs_or_t as times must have shape ({n},), got {t.shape}")
    names = list(channels) if channels is not None else [f"ch{i}" for i in range(len(data))]
    if len(names) != len(data):
        raise ValueError(f"channels must name {len(data)} channel(s), got {len(names)}")
    ax = _axes(ax)
    for row, name in zip(data, names, strict=True):
        ax.plot(t, row, lw=0.6, label=name, alpha=0.9 if len(data) == 1 else 0.75)
    ax.set_xlabel("Time (s)")
    ax.set_ylabel(f"Acceleration ({unit})" if unit else "Amplitude")
    ax.set_xlim(t[0], t[-1])
    ax.grid(True, alpha=0.3)
    if len(data) > 1:
        ax.legend(loc="upper right", fontsize="small", ncols=min(len(data), 4))
    return ax


def _one_signal(x, fs) -> tuple[np.ndarray, float]:
    """``x`` as a finite 1-D float array of at least 16 samples and ``fs`` > 0, or a
    ValueError naming the argument."""
    from .features._validation import check_fs

    fs = check_fs(fs)
    x = np.asarray(x, dtype=float)
    if x.ndim != 1 or x.size < 16 or not np.all(np.isfinite(x)):
        raise ValueError(
            f"x must be one finite signal of at least 16 samples, got shape {x.shape}"
            + ("" if np.all(np.isfinite(x)) else " with NaN or inf")
        )
    return x, fs


def _check_nperseg(nperseg, n_samples: int) -> None:
    if isinstance(nperseg, bool) or not isinstance(nperseg, numbers.Integral) or not (
        16 <= nperseg <= n_samples
    ):
        raise ValueError(f"nperseg must be an int in [16, n_samples={n_samples}], got {nperseg!r}")


def spectrum(x, fs: float, *, db: bool = False, fmax: float | None = None, unit="m/s²",
             ax=None):
    """Plot the one-sided amplitude spectrum of a signal (Hann window).

    A sinusoid of amplitude ``A`` on a bin reads ``A`` (the window's coherent gain is
    divided out), so the plot reads in the signal's unit.

    Parameters
    ----------
    x : array_like, shape (n_samples,)
        Signal, e.g. acceleration in m/s^2; at least 16 samples.
    fs : float
        Sampling frequency, Hz.
    db : bool, optional
        Plot ``20 log10(amplitude)`` (dB re 1 unit) instead of the amplitude.
    fmax : float, optional
        Upper frequency limit, Hz (default fs/2).
    unit : str, optional
        Unit of ``x`` for the y label.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on (default: a new figure).

    Returns
    -------
    matplotlib.axes.Axes

    Examples
    --------
    >>> import numpy as np
    >>> from ballpass.plot import spectrum
    >>> t = np.arange(4800) / 4800.0
    >>> ax = spectrum(2.0 * np.sin(2 * np.pi * 300 * t), 4800.0)
    >>> f, a = ax.lines[0].get_data()
    >>> float(f[np.argmax(a)]), round(float(a.max()), 3)
    (300.0, 2.0)
    """
    x, fs = _one_signal(x, fs)
    window = np.hanning(x.size + 1)[:-1]  # periodic Hann
    amp = 2.0 * np.abs(np.fft.rfft((x - x.mean()) * window)) / window.sum()
    freqs = np.fft.rfftfreq(x.size, 1.0 / fs)
    ax = _axes(ax)
    ax.plot(freqs, 20 * np.log10(np.maximum(amp, 1e-300)) if db else amp, lw=0.8, color="k")
    ax.set_xlim(0, fs / 2 if fmax is None else fmax)
    ax.set_xlabel("Frequency (Hz)")
    ax.set_ylabel(f"Amplitude (dB re 1 {unit})" if db else f"Amplitude ({unit})")
    ax.grid(True, alpha=0.3)
    return ax


def psd(x, fs: float, *, nperseg: int | None = None, unit="m/s²", ax=None):
    """Plot the power spectral density of a signal (Welch, Hann, 50 % overlap), log scale.

    Parameters
    ----------
    x : array_like, shape (n_samples,)
        Signal, e.g. acceleration in m/s^2; at least 16 samples.
    fs : float
        Sampling frequency, Hz.
    nperseg : int, optional
        Segment length, samples (default: the power of two nearest ``fs / 8``, so the
        resolution is about 8 Hz, capped at the signal length).
    unit : str, optional
        Unit of ``x`` for the y label (the PSD is in unit^2/Hz).
    ax : matplotlib.axes.Axes, optional
        Axes to draw on (default: a new figure).

    Returns
    -------
    matplotlib.axes.Axes

    Examples
    --------
    The PSD of white noise of variance 1 integrates to 1:

    >>> import numpy as np
    >>> from ballpass.plot import psd
    >>> ax = psd(np.random.default_rng(0).standard_normal(48_000), 12_000.0)
    >>> f, p = ax.lines[0].get_data()
    >>> round(float(np.sum(p) * (f[1] - f[0])), 1)
    1.0
    """
    import scipy.signal

    x, fs = _one_signal(x, fs)
    if nperseg is None:
        nperseg = min(x.size, 2 ** max(4, round(np.log2(fs / 8))))
    else:
        _check_nperseg(nperseg, x.size)
    freqs, density = scipy.signal.welch(x, fs, nperseg=int(nperseg))
    ax = _axes(ax)
    ax.semilogy(freqs, np.maximum(density, 1e-300), lw=0.8, color="k")
    ax.set_xlim(0, fs / 2)
    ax.set_xlabel("Frequency (Hz)")
    ax.set_ylabel(f"PSD (({unit})²/Hz)")
    ax.grid(True, which="both", alpha=0.3)
    return ax


def spectrogram(x, fs: float, *, nperseg: int = 256, fmax: float | None = None,
                colorbar: bool = True, ax=None):
    """Plot the spectrogram of a signal (Hann, 75 % overlap), in dB.

    Parameters
    ----------
    x : array_like, shape (n_samples,)
        Signal, e.g. acceleration in m/s^2; at least ``nperseg`` samples.
    fs : float
        Sampling frequency, Hz.
    nperseg : int, optional
        Segment length, samples (default 256: 21 ms at 12 kHz).
    fmax : float, optional
        Upper frequency limit, Hz (default fs/2).
    colorbar : bool, optional
        Add a colour bar (default True).
    ax : matplotlib.axes.Axes, optional
        Axes to draw on (default: a new figure).

    Returns
    -------
    matplotlib.axes.Axes

    Examples
    --------
    >>> import numpy as np
    >>> from ballpass.plot import spectrogram
    >>> t = np.arange(12_000) / 12_000.0
    >>> ax = spectrogram(np.sin(2 * np.pi * (500 * t + 1000 * t**2)), 12_000.0)
    >>> ax.get_ylabel()
    'Frequency (Hz)'
    """
    import scipy.signal

    x, fs = _one_signal(x, fs)
    _check_nperseg(nperseg, x.size)
    freqs, times, power = scipy.signal.spectrogram(
        x, fs, window="hann", nperseg=int(nperseg), noverlap=3 * int(nperseg) // 4
    )
    ax = _axes(ax)
    mesh = ax.pcolormesh(times, freqs, 10 * np.log10(np.maximum(power, 1e-300)),
                         shading="nearest", cmap="magma")
    ax.set_ylim(0, fs / 2 if fmax is None else fmax)
    ax.set_xlabel("Time (s)")
    ax.set_ylabel("Frequency (Hz)")
    if colorbar:
        ax.figure.colorbar(mesh, ax=ax, label="PSD (dB re 1 unit²/Hz)", pad=0.01)
    return ax


def _fault_lines(frequencies, lines) -> dict[str, float]:
    """``{name: Hz}`` of the lines to mark, from BearingFrequencies or a dict."""
    if frequencies is None:
        return {}
    if hasattr(frequencies, "as_dict"):  # BearingFrequencies
        table = frequencies.as_dict()
        default = DEFAULT_LINES
    else:
        table = dict(frequencies)
        default = tuple(table)
    unknown = [name for name in lines or () if name not in table]
    if unknown:
        raise ValueError(f"lines must be names in frequencies {sorted(table)}, got {unknown}")
    return {name: float(table[name]) for name in (lines or default)}


def envelope_spectrum(
    freqs,
    amp,
    *,
    frequencies=None,
    harmonics: int = 3,
    lines=None,
    fmax: float | None = None,
    labels=None,
    unit="(m/s²)²",
    ax=None,
):
    """Plot an envelope spectrum with labelled fault-frequency markers.

    Each fault line gets a colour and dashed markers at harmonics ``1..harmonics``,
    numbered at the top; the legend gives its name and frequency. The range shown
    reaches a little above the highest of them, and the defect families (BPFO, BPFI,
    2xBSF, BSF) are marked at every harmonic inside it, so no line of theirs in view
    is left unmarked beside another family's marker; shaft and cage lines keep
    ``harmonics``.

    Parameters
    ----------
    freqs : array_like, shape (n_bins,)
        Frequencies, Hz.
    amp : array_like, shape (n_bins,) or (n_spectra, n_bins)
        Envelope spectrum amplitude(s).
    frequencies : BearingFrequencies or dict of str to float, optional
        Fault frequencies in Hz, e.g. ``Bearing.catalog("6205").frequencies(29.95)``.
        Known names (``shaft``, ``ftf``, ``bpfo``, ``bpfi``, ``bsf``, ``ball_defect``)
        get fixed colours and labels.
    harmonics : int, optional
        Harmonics to mark per line (default 3); with the default ``fmax`` the plot
        reaches 1.1 times the highest of them.
    lines : sequence of str, optional
        Which entries of ``frequencies`` to mark (default: shaft, FTF, BPFO, BPFI and
        2×BSF for BearingFrequencies; every entry of a dict).
    fmax : float, optional
        Upper frequency limit, Hz (default: a little above the highest marker, or
        the whole spectrum without markers).
    labels : sequence of str, optional
        Legend labels of the spectra when there are several.
    unit : str, optional
        Unit of ``amp`` for the y label (default ``"(m/s²)²"``, the SES of m/s²).
    ax : matplotlib.axes.Axes, optional
        Axes to draw on (default: a new figure).

    Returns
    -------
    matplotlib.axes.Axes

    Examples
    --------
    >>> import numpy as np
    >>> from ballpass.plot import envelope_spectrum
    >>> f = np.arange(1001) * 0.5
    >>> ax = envelope_spectrum(f, np.exp(-f / 50), frequencies={"BPFO": 107.3}, harmonics=2)
    >>> [t.get_text() for t in ax.texts]
    ['1×', '2×']
    """
    freqs = np.asarray(freqs, dtype=float)
    spectra = np.atleast_2d(np.asarray(amp, dtype=float))
    if freqs.ndim != 1 or spectra.shape[-1] != freqs.size:
        raise ValueError(
            f"amp must have shape (n_bins,) or (n, n_bins) with n_bins = len(freqs) = "
            f"{freqs.size}, got {spectra.shape}"
        )
    if isinstance(harmonics, bool) or not isinstance(harmonics, numbers.Integral) or harmonics < 1:
        raise ValueError(f"harmonics must be an int >= 1, got {harmonics!r}")
    marks = _fault_lines(frequencies, lines)
    if fmax is None:
        fmax = min(freqs[-1], 1.1 * harmonics * max(marks.values())) if marks else freqs[-1]
    ax = _axes(ax)
    keep = freqs <= fmax
    names = list(labels) if labels is not None else [None] * len(spectra)
    for spectrum, label in zip(spectra, names, strict=True):
        ax.plot(
            freqs[keep],
            spectrum[keep],
            lw=0.8,
            color="k" if len(spectra) == 1 else None,
            label=label,
        )
    transform = ax.get_xaxis_transform()
    placed: list[float] = []  # harmonic numbers closer than 2 % of the axis are skipped
    for i, (name, f0) in enumerate(marks.items()):
        text, colour = LINE_STYLE.get(name, (name, f"C{i % 10}"))
        minor = name in ("shaft", "ftf")
        last = harmonics if minor else max(harmonics, int(fmax // f0))
        for h in range(1, last + 1):
            if h * f0 > fmax:
                break
            ax.axvline(
                h * f0,
                color=colour,
                ls=":" if minor else "--",
                lw=0.8 if minor else 1.0,
                alpha=0.7 if minor else 0.85,
                label=f"{text} {f0:.1f} Hz" if h == 1 else None,
            )
            if all(abs(h * f0 - p) > 0.02 * fmax for p in placed):
                placed.append(h * f0)
                ax.text(
                    h * f0,
                    1.0,
                    f"{h}×",
                    transform=transform,
                    color=colour,
                    ha="center",
                    va="bottom",
                    fontsize="x-small",
                )
    ax.set_xlim(0, fmax)
    ax.set_ylim(bottom=0)
    ax.set_xlabel("Frequency (Hz)")
    ax.set_ylabel(f"Amplitude ({unit})" if unit else "Amplitude")
    ax.grid(True, alpha=0.3)
    if marks or labels is not None:
        ax.legend(loc="upper right", fontsize="small", framealpha=0.85)
    return ax


def kurtogram(result, *, ax=None, colorbar: bool = True, band_used=None, legend: bool = True):
    """Plot a fast-kurtogram heat map with the selected band outlined.

    Bands without content (power density below the result's ``floor_db``) are grey
    and excluded from the colour scale; the other bands the automatic choice skips
    (too narrow, reaching fs/2, or below the fault lines) are drawn faded. A note
    under the map says so. The kurtogram's best band is outlined in white; a band
    that was used instead (``band_used``, e.g. one given by the caller) is outlined
    dashed.

    Parameters
    ----------
    result : KurtogramResult
        From :func:`ballpass.features.fast_kurtogram` of one signal.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on (default: a new figure).
    colorbar : bool, optional
        Add a colour bar (default True).
    band_used : (float, float), optional
        A demodulation band, Hz, used instead of the best band: outlined dashed across
        the map's height, and named in the title.
    legend : bool, optional
        Write the note that explains the grey and faded cells (default True).

    Returns
    -------
    matplotlib.axes.Axes

    Examples
    --------
    >>> import numpy as np
    >>> from ballpass.features import fast_kurtogram
    >>> from ballpass.plot import kurtogram
    >>> res = fast_kurtogram(np.random.default_rng(0).standard_normal(4096), 1000.0)
    >>> kurtogram(res).get_ylabel()
    'Level (bandwidth)'
    """
    grid = np.asarray(result.kurtosis)
    if grid.ndim != 2:
        raise ValueError(
            f"kurtogram plots one signal's result; got a kurtosis grid of shape {grid.shape}"
        )
    ax = _axes(ax)
    n_rows = grid.shape[0]
    content = np.asarray(result.density_db) >= result.floor_db
    cmap = _pyplot().get_cmap("viridis").with_extremes(bad="0.8")
    extent = (0.0, 0.5 * result.fs, n_rows - 0.5, -0.5)
    image = ax.imshow(
        np.ma.masked_where(~content, grid),
        aspect="auto",
        cmap=cmap,
        interpolation="nearest",
        extent=extent,
        vmin=min(0.0, float(grid[content].min())),
        vmax=float(grid[content].max()),
    )
    faded = np.zeros(grid.shape + (4,))
    faded[content & ~np.asarray(result.admissible)] = (1.0, 1.0, 1.0, 0.55)
    ax.imshow(faded, aspect="auto", interpolation="nearest", extent=extent)
    ax.set_yticks(np.arange(n_rows))
    ax.set_yticklabels(
        [f"{lv:.1f} ({_hz(bw)})" for lv, bw in zip(result.levels, result.bandwidths, strict=True)],
        fontsize="x-small",
    )
    lo, hi = result.best_band
    row = int(np.flatnonzero(np.isclose(result.levels, result.best_level))[0])
    ax.add_patch(_rectangle((lo, row - 0.5), hi - lo, 1.0))
    title = f"Kurtogram: best band {lo:.0f}–{hi:.0f} Hz, SK = {result.best_kurtosis:.2f}"
    if band_used is not None and tuple(map(float, band_used)) != (float(lo), float(hi)):
        used_lo, used_hi = map(float, band_used)
        ax.add_patch(_rectangle((used_lo, -0.5), used_hi - used_lo, n_rows, ls="--"))
        title += f"\n(dashed: band used, {used_lo:.0f}–{used_hi:.0f} Hz)"
    ax.set_xlabel("Frequency (Hz)")
    ax.set_ylabel("Level (bandwidth)")
    ax.set_title(title, fontsize="medium")
    if legend:
        ax.text(0.0, -0.18, f"grey: no content (< {result.floor_db:g} dB of the mean density)\n"
                "faded: skipped (too narrow, at fs/2, or below the fault lines)",
                transform=ax.transAxes, fontsize="x-small", va="top")
    if colorbar:
        ax.figure.colorbar(image, ax=ax, label="Spectral kurtosis", pad=0.01)
    return ax


def _ses_beside_kurtogram(ax_ses, ax_k, freqs, ses, result, bands, *, rule=None,
                         frequencies=None, harmonics: int = 3, labels=None) -> None:
    """Draw a squared envelope spectrum titled with its band beside the kurtogram.

    The pair of :func:`signal_overview` and ``EnvelopeAnalysis.plot``: the spectrum's
    title names the band(s) it was demodulated in (and the rule that chose them), the
    kurtogram outlines its best band and, dashed, the first band used when different.

    Parameters
    ----------
    ax_ses, ax_k : matplotlib.axes.Axes
        Axes of the spectrum and of the kurtogram.
    freqs : array_like, shape (n_bins,)
        Frequencies of the spectrum, Hz.
    ses : array_like, shape (n_bins,) or (n_spectra, n_bins)
        Squared envelope spectrum (or one per channel), (m/s^2)^2.
    result : KurtogramResult
        The kurtogram drawn (of the first signal).
    bands : sequence of (float, float)
        Demodulation band of each spectrum, Hz.
    rule : str, optional
        What chose the band(s), for the title (default: not said).
    frequencies, harmonics, labels
        As in :func:`envelope_spectrum`.
    """
    envelope_spectrum(freqs, ses, frequencies=frequencies, harmonics=harmonics,
                      labels=labels, ax=ax_ses)
    distinct = list(dict.fromkeys((float(lo), float(hi)) for lo, hi in bands))
    text = ", ".join(f"{lo:.0f}–{hi:.0f} Hz" for lo, hi in distinct)
    ax_ses.set_title(f"Squared envelope spectrum (band {text}{f': {rule}' if rule else ''})",
                     fontsize="medium", loc="left", pad=14)
    kurtogram(result, ax=ax_k, band_used=bands[0])


def _hz(value: float) -> str:
    return f"{value / 1000:.3g} kHz" if value >= 1000 else f"{value:.3g} Hz"


def _rectangle(xy, width, height, ls="-"):
    from matplotlib.patches import Rectangle

    return Rectangle(xy, width, height, fill=False, edgecolor="white", lw=1.8, ls=ls)


def signal_overview(
    x,
    fs: float,
    bearing=None,
    shaft_hz: float | None = None,
    path=None,
    *,
    channels=None,
    band=None,
    band_source: str = "given",
    harmonics: int = 3,
    title: str | None = None,
    dpi: int = 120,
):
    """One figure: waveform, squared envelope spectrum with fault markers, kurtogram.

    The demodulation band of each channel is chosen by the fast kurtogram unless
    ``band`` is given; the kurtogram of the first channel is drawn, with the band its
    spectrum used outlined (white: the kurtogram's choice; dashed: a given band).
    With a bearing the kurtogram chooses among bands above the fault lines marked
    (:func:`ballpass.features.envelope_analysis`). The spectrum's title says which rule
    chose its band.

    Parameters
    ----------
    x : array_like, shape (n_samples,) or (n_channels, n_samples)
        Acceleration, m/s^2.
    fs : float
        Sampling frequency, Hz.
    bearing : str or Bearing, optional
        Bearing whose fault frequencies are marked (needs ``shaft_hz``).
    shaft_hz : float, optional
        Shaft speed, Hz (rpm / 60).
    path : str or os.PathLike, optional
        Save the figure there (PNG, or any format matplotlib infers from the suffix).
    channels : sequence of str, optional
        Channel names.
    band : (float, float), optional
        Demodulation band, Hz, for every channel.
    band_source : str, optional
        Where a given ``band`` comes from, for the spectrum's title (default
        ``"given"``; ``ballpass simulate`` says "the sensor resonance's band").
    harmonics : int, optional
        Harmonics of each fault line to mark (default 3).
    title : str, optional
        Figure title.
    dpi : int, optional
        Resolution of the saved image (default 120).

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import numpy as np
    >>> from ballpass.plot import signal_overview
    >>> x = np.random.default_rng(0).standard_normal(12_000)
    >>> fig = signal_overview(x, 12_000.0, bearing="6205", shaft_hz=29.95)
    >>> len(fig.axes)
    4
    """
    from matplotlib.figure import Figure

    from . import features
    from .features.bands import as_bearing

    data = np.atleast_2d(np.asarray(x, dtype=float))
    names = (
        list(channels)
        if channels is not None
        else (["signal"] if len(data) == 1 else [f"ch{i}" for i in range(len(data))])
    )
    if (bearing is None) != (shaft_hz is None):
        raise ValueError("bearing and shaft_hz go together: give both or neither")
    bearing = as_bearing(bearing) if bearing is not None else None
    marks = bearing.frequencies(float(shaft_hz)) if bearing is not None else None
    lines = {} if bearing is None else {"rpm": 60.0 * float(shaft_hz), "bearing": bearing}
    if band is None:  # one envelope analysis per channel: kurtogram, band and SES
        analyses = [features.envelope_analysis(row, fs, **lines) for row in data]
        result = analyses[0].kurtogram
        bands = [a.band for a in analyses]
        spectra = [(a.freqs, a.ses) for a in analyses]
        rule = "the kurtogram's best" + (" above the fault lines" if lines else "")
    else:
        result = features.envelope_analysis(data[0], fs, **lines).kurtogram
        bands = [tuple(map(float, band))] * len(data)
        spectra = [features.envelope_spectrum(row, fs, band) for row in data]
        rule = band_source

    fig = Figure(figsize=(12, 7.5), layout="constrained")
    grid = fig.add_gridspec(2, 2, height_ratios=(1, 1.35), width_ratios=(1.5, 1))
    ax_wave = fig.add_subplot(grid[0, :])
    waveform(data, fs, channels=names if len(data) > 1 else None, ax=ax_wave)
    ax_wave.set_title("Waveform", fontsize="medium", loc="left")

    _ses_beside_kurtogram(fig.add_subplot(grid[1, 0]), fig.add_subplot(grid[1, 1]),
                         spectra[0][0], np.stack([s[1] for s in spectra]), result, bands,
                         rule=rule, frequencies=marks, harmonics=harmonics,
                         labels=names if len(data) > 1 else None)
    if title is None:
        parts = [f"fs {fs:g} Hz, {data.shape[-1] / fs:g} s"]
        if bearing is not None:
            parts.insert(
                0, f"bearing {bearing.name}, shaft {shaft_hz:.2f} Hz ({60 * shaft_hz:.0f} rpm)"
            )
        title = "  ·  ".join(parts)
    fig.suptitle(title)
    if path is not None:
        path = Path(path)
        path.parent.mkdir(parents=True, exist_ok=True)
        fig.savefig(path, dpi=dpi)
    return fig
