"""A diagnosis to look at: the squared envelope spectrum with the lines the diagnoser read.

:func:`plot_explanation` draws the squared envelope spectrum (SES) of one signal in the
band where a fault family read highest, and marks that family's lines where the
diagnoser found them: carriers solid and labelled with their level above the background,
supporting sidebands dashed, sidebands that count against the family dotted, and lines
left out (shared with another family, on a shaft harmonic) in grey. A family the
diagnoser could not judge is shown in the band of the fast kurtogram.
"""

from __future__ import annotations

import numpy as np

from ..features import envelope_spectrum
from ..features._validation import check_fs, check_signal
from ..plot import LINE_STYLE
from .evidence import FAULT_FAMILIES
from .rules import Explanation

__all__ = ["plot_explanation"]


def _family_to_show(explanation: Explanation, family: str | None) -> str:
    """The family named, else the verdict, else (healthy) the one closest to its
    threshold among those judged, else the outer race."""
    if family is not None:
        if family not in FAULT_FAMILIES:
            raise ValueError(f"family must be one of {list(FAULT_FAMILIES)} or None, "
                             f"got {family!r}")
        return family
    if explanation.label in FAULT_FAMILIES:
        return explanation.label
    margins = {f: explanation.evidence_db[f] - explanation.threshold_db[f]
               for f in FAULT_FAMILIES if np.isfinite(explanation.evidence_db[f])}
    return max(margins, key=margins.get) if margins else "outer"


def plot_explanation(x, fs: float, explanation: Explanation, *, family: str | None = None,
                     ax=None):
    """Plot the SES behind a diagnosis with the lines the diagnoser read.

    Parameters
    ----------
    x : array_like, shape (n_samples,)
        The signal that was explained, sampled at ``fs`` (m/s^2).
    fs : float
        Sampling frequency, Hz.
    explanation : Explanation
        ``EnvelopeDiagnoser(...).explain(x[None])[0]``.
    family : {"outer", "inner", "ball"}, optional
        Family whose band and lines to show; default the verdict, or for "healthy" the
        family that came closest to its threshold.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; a new figure (without pyplot) when omitted.

    Returns
    -------
    matplotlib.axes.Axes

    Examples
    --------
    >>> import numpy as np
    >>> import ballpass as bp
    >>> from ballpass.diagnose import EnvelopeDiagnoser, plot_explanation
    >>> fs, rpm = 12_000.0, 1797.0
    >>> bpfo = bp.Bearing.catalog("6205").frequencies(rpm / 60).bpfo
    >>> t = np.arange(24_000) / fs
    >>> phase = (t * bpfo) % 1.0 / bpfo                      # time since the last impact, s
    >>> x = np.exp(-800 * phase) * np.sin(2 * np.pi * 3000 * phase)
    >>> x = x + 0.2 * np.random.default_rng(0).standard_normal(t.size)
    >>> why = EnvelopeDiagnoser(fs=fs, rpm=rpm).explain(x[None])[0]
    >>> ax = plot_explanation(x, fs, why)
    >>> ax.get_title().splitlines()[0]
    'outer (grade Y) at 1797 rpm'
    >>> ax.figure.savefig("outer.png")                      # doctest: +SKIP
    """
    fs = check_fs(fs)
    xv = check_signal(x)
    if xv.ndim != 1:
        raise ValueError(f"x must be one signal of shape (n_samples,), got {xv.shape}")
    if not isinstance(explanation, Explanation):
        raise TypeError("explanation must be an Explanation from EnvelopeDiagnoser.explain, "
                        f"got {type(explanation).__name__}")
    shown = _family_to_show(explanation, family)
    band = explanation.band_hz[shown]
    judged = bool(np.all(np.isfinite(band)))
    freqs, ses = envelope_spectrum(xv, fs, tuple(band) if judged else None)
    lines = explanation.lines[explanation.lines.fault == shown]
    fmax = 1.15 * float(lines.nominal_hz.max())
    keep = (freqs > 0) & (freqs <= fmax)
    if ax is None:
        from matplotlib.figure import Figure

        ax = Figure(figsize=(8, 3.5), layout="constrained").add_subplot()
    ax.plot(freqs[keep], ses[keep], color="k", lw=0.8)
    colour = LINE_STYLE[FAULT_FAMILIES[shown][0]][1]
    for row in lines.itertuples(index=False):
        counted = np.isfinite(row.level_db)
        where = row.found_hz if counted and np.isfinite(row.found_hz) else row.nominal_hz
        style = {"carrier": "-", "sideband": "--"}.get(row.role, ":")
        ax.axvline(where, color=colour if counted else "0.6", ls=style,
                   lw=1.2 if row.role == "carrier" else 0.9, alpha=0.85)
        if row.role == "carrier":
            text = f"{row.line}\n{row.level_db:+.1f} dB" if counted else f"{row.line}\nleft out"
            ax.text(where, 0.98, text, transform=ax.get_xaxis_transform(), ha="center",
                    va="top", fontsize="x-small", color=colour if counted else "0.4")
    ev, thr = explanation.evidence_db[shown], explanation.threshold_db[shown]
    where_band = (f"band {band[0]:g}-{band[1]:g} Hz" if judged
                  else "not judged (SES of the kurtogram's band)")
    ax.set_title(f"{explanation.label} (grade {explanation.grade}) at "
                 f"{explanation.rpm:.0f} rpm\n{shown}: evidence {ev:.1f} dB, threshold "
                 f"{thr:.1f} dB, {where_band}", fontsize="small")
    ax.set_xlim(0, fmax)
    ax.set_ylim(bottom=0)
    ax.set_xlabel("Frequency (Hz)")
    ax.set_ylabel("SES ((m/s²)²)")
    ax.grid(True, alpha=0.3)
    return ax
