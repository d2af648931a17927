"""Write the .mat fixtures of tests/data/cwru_mat and tests/data/mfpt_mat (see README.md).

Run from the repository root with the full recordings in ../shared/data:

    python tests/data/make_mat_crops.py

Real crops keep the source variables' names, dtypes (float64, uint16 RPM) and layout
(column vectors); synthetic files are built from real crops and say so in a variable
``provenance``.
"""

from pathlib import Path

import numpy as np
import scipy.io
import scipy.signal

HERE = Path(__file__).parent
SHARED = HERE.parents[2] / "shared" / "data"


def crop_cwru(source, n, channels=("DE",)):
    """The first n samples of the given channels of a CWRU file, and its RPM variable."""
    d = scipy.io.loadmat(SHARED / "cwru" / source)
    out = {k: d[k][:n] for k in d if any(k.endswith(f"_{c}_time") for c in channels)}
    out |= {k: d[k] for k in d if k.endswith("RPM")}
    return out


def renumber(data, old, new, rpm=True):
    """Variables of record ``old`` renamed to record ``new`` (RPM dropped if not rpm)."""
    out = {}
    for key, value in data.items():
        if key.endswith("RPM") and not rpm:
            continue
        out[key.replace(f"X{old:03d}", f"X{new:03d}")] = value
    return out


def main():
    cwru, mfpt = HERE / "cwru_mat", HERE / "mfpt_mat"
    cwru.mkdir(exist_ok=True)
    mfpt.mkdir(exist_ok=True)

    def save(folder, name, data):
        scipy.io.savemat(folder / name, data, do_compression=True)

    n12, n48 = 3000, 6000  # 0.25 s at 12 kHz, 0.125 s at 48 kHz
    ir = crop_cwru("12k_DE_IR007_0.mat", n12)
    save(cwru, "12k_DE_IR007_0.mat", ir)
    save(cwru, "105.mat", ir)
    save(cwru, "12k_DE_OR007@6_0.mat", crop_cwru("12k_DE_OR007@6_0.mat", n12))
    save(cwru, "12k_FE_OR007@12_0.mat", crop_cwru("12k_FE_OR007@12_0.mat", n12, ("DE", "FE")))
    save(cwru, "12k_FE_OR014@3_0.mat", crop_cwru("12k_FE_OR014@3_0.mat", n12, ("DE", "FE")))
    normal = crop_cwru("Normal_0_48k.mat", n48)
    for name in ("97.mat", "Normal_0.mat", "Normal_Normal_0.mat"):
        save(cwru, name, normal)
    # synthetic: a 0.028 in file has no RPM variable; record 3003 = 12 kHz DE IR028 at 2 hp
    ir021 = crop_cwru("12k_DE_IR021_0.mat", n12)
    save(cwru, "12k_DE_IR028_2.mat", renumber(ir021, 209, 3003, rpm=False)
         | {"provenance": "synthetic: 12k_DE_IR021_0 samples 0-2999 renamed X3003, no RPM"})
    # synthetic 48 kHz fault file: record 123 = 48 kHz DE B007 at 1 hp, stored 1772 rpm
    b007 = crop_cwru("12k_DE_B007_0.mat", n12)
    x48 = scipy.signal.resample_poly(b007["X118_DE_time"].ravel(), 4, 1)[:, None]
    save(cwru, "48k_DE_B007_1.mat", {
        "X123_DE_time": x48, "X123RPM": np.array([[1772]], dtype=np.uint16),
        "provenance": "synthetic: 12k_DE_B007_0 samples 0-2999 upsampled 4x, RPM 1772 set",
    })

    nm = 24414  # 0.5 s at 48828 Hz
    for name in ("InnerRaceFault_vload_1.mat", "OuterRaceFault_vload_1.mat"):
        d = scipy.io.loadmat(SHARED / "mfpt" / name)
        b = d["bearing"][0, 0]
        struct = {f: b[f] for f in b.dtype.names}
        struct["gs"] = struct["gs"][:nm]
        save(mfpt, name, {"bearing": struct} | {k: d[k] for k in ("BPFO", "BPFI", "FTF", "BSF")})


if __name__ == "__main__":
    main()
