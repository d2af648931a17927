"""Diagnostic features of bearing vibration.

Functions work on arrays of shape ``(..., n_samples)`` along ``axis=-1`` with the
sampling frequency ``fs`` in Hz, like :mod:`scipy.signal`; those with a frequency
axis return ``(freqs, values)``.

Envelope analysis
-----------------
envelope_analysis          kurtogram, band, SES, indicators (and fault bands) in one call
envelope_spectrum          (squared) envelope spectrum; SES by default, band from the kurtogram
squared_envelope_spectrum  the SES, explicitly
envelope                   Hilbert envelope of the band-passed signal
bandpass                   zero-phase Butterworth band-pass
cepstrum_prewhiten         cepstrum pre-whitening (Borghesani et al. 2013)

Order tracking (variable speed)
-------------------------------
order_envelope_spectrum    envelope spectrum in shaft orders
order_track                resample to uniform shaft angle
shaft_revolutions          shaft angle from an rpm profile or a tachometer

Discrete/random separation
--------------------------
separate_discrete          (discrete, residual): TSA subtraction, linear prediction, DRS

Spectral kurtosis
-----------------
fast_kurtogram             1/3-binary fast kurtogram (Antoni 2007) -> KurtogramResult
spectral_kurtosis          STFT-based spectral kurtosis (Antoni 2006)

Indicators and fault bands
--------------------------
indicators                 rms, peak, crest factor, kurtosis, skewness, ...
indicator_ratios           faulty/healthy ratio of each indicator
fault_band_features        SES levels (dB) at BPFO, BPFI, BSF, 2xBSF, FTF and BPFI sidebands
fault_band_levels          the same, from a given SES
fault_band_names           names of those features

scikit-learn
------------
IndicatorTransformer, FaultBandTransformer

Examples
--------
>>> import numpy as np
>>> import ballpass as bp
>>> x = np.random.default_rng(0).standard_normal(12_000)
>>> freqs, ses = bp.features.envelope_spectrum(x, 12_000.0, band=(2000, 4000))
>>> sorted(bp.features.indicators(x))[:3]
['clearance_factor', 'crest_factor', 'impulse_factor']
"""

from .analysis import EnvelopeAnalysis, envelope_analysis
from .bands import FAULT_LINES, fault_band_features, fault_band_levels, fault_band_names
from .envelope import (
    bandpass,
    cepstrum_prewhiten,
    envelope,
    envelope_spectrum,
    squared_envelope_spectrum,
)
from .indicators import INDICATORS, indicator_ratios, indicators
from .kurtogram import KurtogramResult, fast_kurtogram, spectral_kurtosis
from .order import order_envelope_spectrum, order_track, shaft_revolutions
from .separation import SEPARATION_METHODS, separate_discrete

#: Defined in .transformers; loaded on first use, because importing scikit-learn
#: costs about a second that the plain functions do not need.
_LAZY = {"FaultBandTransformer", "IndicatorTransformer"}

__all__ = [
    "FAULT_LINES",
    "INDICATORS",
    "EnvelopeAnalysis",
    "FaultBandTransformer",
    "IndicatorTransformer",
    "KurtogramResult",
    "SEPARATION_METHODS",
    "bandpass",
    "cepstrum_prewhiten",
    "envelope",
    "envelope_analysis",
    "envelope_spectrum",
    "fast_kurtogram",
    "fault_band_features",
    "fault_band_levels",
    "fault_band_names",
    "indicator_ratios",
    "indicators",
    "order_envelope_spectrum",
    "order_track",
    "separate_discrete",
    "shaft_revolutions",
    "spectral_kurtosis",
    "squared_envelope_spectrum",
]


def __getattr__(name: str):
    if name in _LAZY:
        from . import transformers

        return getattr(transformers, name)
    raise AttributeError(f"module 'ballpass.features' has no attribute {name!r}")
