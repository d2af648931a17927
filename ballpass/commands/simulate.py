"""``ballpass simulate``: one scene to a signal file, optionally with a plot."""

from __future__ import annotations

import argparse

EXAMPLE = """\
examples:
  ballpass simulate --fault outer --rpm 1797 --out outer.npz --plot outer.png
  ballpass simulate --bearing 6205 --fault inner --width 0.53 --depth 0.1 \\
      --fs 12000 --resonance 3000 --duration 2 --out inner.csv
  ballpass simulate --fault ball --sensors loaded unloaded --snr 10 --out ball.parquet
  ballpass simulate --bearing 6208 --rpm 2000 --fault inner --gears tran-furch-cu-1st \\
      --torque 80 --fs 24000 --resonance 3000 --out gearbox.npz
"""


def add_parser(subparsers) -> argparse.ArgumentParser:
    """Register ``simulate`` on the ``ballpass`` command."""
    p = subparsers.add_parser(
        "simulate",
        help="simulate one scene and write its signal (.npz/.csv/.parquet)",
        description="Simulate a bearing and write the acceleration at each sensor (m/s^2). "
        "The model is the cheapest that represents what the scene needs (--model auto; "
        "`ballpass models` lists them). The output format follows the extension.",
        epilog=EXAMPLE,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    add_scene_arguments(p)
    from ..gears import GEAR_PRESETS, PRESET_ALIASES

    p.add_argument("--gears", choices=[*GEAR_PRESETS, *PRESET_ALIASES], default=None,
                   help="a gear pair whose pinion sits on the bearing's shaft (Tran, Furch & Cu "
                   "Table 1 presets); runs the gearbox model")
    p.add_argument("--torque", type=float, default=None,
                   help="input torque of the gear pair, N m (default: the preset's, 50)")
    from ..phenomena import PHENOMENA

    p.add_argument("--model", default="auto",
                   help="auto (default: the cheapest model that represents --needs) or a "
                   "model name from `ballpass models`, e.g. impulse, sr5, multibody")
    p.add_argument("--needs", nargs="+", metavar="PHENOMENON", choices=sorted(PHENOMENA),
                   default=None, help="phenomena the signal must show, for --model auto: "
                   + ", ".join(sorted(PHENOMENA)) + " (default: envelope, contact_dynamics)")
    p.add_argument("--solver", default="auto",
                   help="auto (default: the model's own) or one of the model's solvers "
                   "(`ballpass models`)")
    p.add_argument("--dt", type=float, default=None,
                   help="step of a fixed-step solver, s (default: automatic)")
    p.add_argument("--rtol", type=float, default=None,
                   help="relative tolerance of an adaptive solver")
    p.add_argument("--out", "-o", required=True, help="output file: .npz, .csv or .parquet")
    p.add_argument("--plot", default=None, metavar="PNG",
                   help="also draw waveform, squared envelope spectrum and kurtogram")
    p.set_defaults(func=run)
    return p


def add_scene_arguments(p: argparse.ArgumentParser) -> None:
    """The scene options shared by ``simulate`` and ``work-precision``."""
    p.add_argument("--bearing", default="6205", help="catalogue designation (default 6205)")
    p.add_argument("--rpm", type=float, nargs="+", default=[1797.0],
                   help="shaft speed, rpm; two values for a linear ramp (default 1797)")
    p.add_argument("--load", type=float, default=500.0, help="radial load, N (default 500)")
    p.add_argument("--fault", choices=["healthy", "outer", "inner", "ball"], default="outer",
                   help="fault kind (default outer)")
    p.add_argument("--width", type=float, default=None, help="fault width, mm (default 0.5)")
    p.add_argument("--depth", type=float, default=None, help="fault depth, mm (default 0.1)")
    p.add_argument("--angle", type=float, default=None,
                   help="fault angle from the load line, deg (default 0)")
    p.add_argument("--duration", type=float, default=1.0, help="seconds (default 1)")
    p.add_argument("--fs", type=float, default=48_000.0, help="sampling rate, Hz (default 48000)")
    p.add_argument("--resonance", type=float, default=15_000.0,
                   help="structural resonance, Hz; must be < 0.45 fs (default 15000)")
    p.add_argument("--damping", type=float, default=0.05,
                   help="damping ratio of the resonance (default 0.05)")
    p.add_argument("--slip", type=float, default=0.01, help="random slip, fraction (0.01)")
    p.add_argument("--sensors", nargs="+", default=["loaded"],
                   help="sensor names (loaded, unloaded) or angles in degrees")
    p.add_argument("--snr", type=float, default=None, help="add noise at this SNR, dB")
    p.add_argument("--seed", type=int, default=0, help="random seed (default 0)")


#: the option that sets each Scene, Fault or GearPair field, for errors that name what
#: the user typed ("--width: width_mm must be ...")
OPTION_OF = {"rpm": "--rpm", "rpm_start": "--rpm", "rpm_end": "--rpm",
             "radial_load_n": "--load", "width_mm": "--width", "depth_mm": "--depth",
             "angle_deg": "--angle", "duration_s": "--duration", "fs": "--fs",
             "resonance_hz": "--resonance", "resonance_damping": "--damping",
             "slip": "--slip", "snr_db": "--snr", "seed": "--seed", "torque_nm": "--torque",
             "model": "--model", "solver": "--solver", "dt": "--dt", "rtol": "--rtol"}


def named_as_typed(exc: ValueError, option_of: dict = OPTION_OF) -> ValueError:
    """``exc`` with the option that sets the field its message starts with put first
    ("--width: width_mm must be ..."), or ``exc`` itself."""
    import re

    field = re.match(r"\w+", str(exc))
    if field and field[0] in option_of:
        return ValueError(f"{option_of[field[0]]}: {exc}")
    return exc


def scene_from_args(args):
    """Build the :class:`~ballpass.Scene` the scene options describe; an invalid value
    is refused naming its option."""
    try:
        return _scene_from_args(args)
    except ValueError as exc:
        raise named_as_typed(exc) from None


def _scene_from_args(args):
    import ballpass as bp

    if len(args.rpm) not in (1, 2):
        raise ValueError(f"--rpm takes one speed or two (a ramp), got {args.rpm}")
    try:
        bp.Bearing.catalog(args.bearing)
    except ValueError as exc:
        raise ValueError(f"--bearing: {exc}") from None
    rpm = args.rpm[0] if len(args.rpm) == 1 else tuple(args.rpm)
    shape = {"--width": args.width, "--depth": args.depth, "--angle": args.angle}
    fault = None
    if args.fault == "healthy":
        given = [name for name, value in shape.items() if value is not None]
        if given:
            verb = "describes" if len(given) == 1 else "describe"
            raise ValueError(f"{', '.join(given)} {verb} a fault; a healthy bearing has "
                             "none (give --fault outer, inner or ball)")
    else:
        width, depth, angle = (d if v is None else v
                               for v, d in zip(shape.values(), (0.5, 0.1, 0.0), strict=True))
        fault = bp.Fault(args.fault, width_mm=width, depth_mm=depth, angle_deg=angle)
    sensors = []
    for s in args.sensors:
        try:
            sensors.append(bp.Sensor(angle_deg=float(s)))
        except ValueError:
            sensors.append(s)
    gears = getattr(args, "gears", None)
    torque = getattr(args, "torque", None)
    if torque is not None and gears is None:
        raise ValueError("--torque applies to a gear pair: give --gears too")
    if gears is not None:
        gears = bp.GearPair.preset(gears, **({} if torque is None else {"torque_nm": torque}))
    return bp.Scene(
        bearing=args.bearing, rpm=rpm, radial_load_n=args.load, fault=fault, gears=gears,
        duration_s=args.duration, fs=args.fs, seed=args.seed, slip=args.slip,
        resonance_hz=args.resonance, resonance_damping=args.damping, sensors=tuple(sensors),
        snr_db=args.snr, needs=tuple(getattr(args, "needs", None) or ()),
    )


def run(args) -> int:
    """Simulate, write the signal file and, with ``--plot``, the overview figure.

    Both output paths are checked before the simulation; the signal and the figure are
    written all or nothing.
    """
    import dataclasses

    import ballpass as bp
    from ballpass.signalio import SUFFIXES, atomic_write_many, signal_writer

    from ._output import FIGURE_SUFFIXES, check_output_path, compile_notice, figure_writer

    out = check_output_path(args.out, option="--out", suffixes=SUFFIXES)
    plot = None if args.plot is None else check_output_path(
        args.plot, option="--plot", suffixes=FIGURE_SUFFIXES)
    scene = scene_from_args(args)
    compile_notice()
    try:   # the model and solver arguments are checked before the simulation starts
        res = bp.simulate(scene, model=args.model, solver=args.solver, dt=args.dt,
                          rtol=args.rtol)
    except ValueError as exc:
        raise named_as_typed(exc) from None
    freqs = res.truth.frequencies
    meta = {
        "bearing": scene.bearing.name,
        "rpm": scene.speed.mean_rpm,
        "label": res.truth.label,
        "faults": [dataclasses.asdict(f) for f in scene.faults],
        "frequencies_hz": freqs.as_dict(),
        "info": res.info,
    }
    writes = [(out, signal_writer(out, res.accel, res.fs, channels=list(res.sensor_names),
                                  meta=meta))]
    if plot is not None:
        from ballpass.plot import signal_overview

        title = (f"{scene.bearing.name} {res.truth.label} at {scene.speed.mean_rpm:g} rpm, "
                 f"{scene.radial_load_n:g} N")
        fig = signal_overview(res.accel, res.fs, bearing=scene.bearing,
                              shaft_hz=scene.shaft_hz, channels=list(res.sensor_names),
                              title=title, band=scene.demodulation_band,
                              band_source="the sensor resonance's band")
        writes.append((plot, figure_writer(fig, plot)))
    atomic_write_many(writes)
    info = res.info
    print(f"{res.truth.label}: {len(res.t)} samples x {len(res.sensor_names)} sensor(s) at "
          f"{res.fs:g} Hz, model {info['model']}, solver {info['solver']}, "
          + (f"{info['n_steps']} steps " if "n_steps" in info else "")
          + f"in {info['wall_time_s']:.2f} s -> {out}")
    if info.get("compile_time_s", 0.0) > 0.5:
        print(f"(compiling the simulator's kernels took {info['compile_time_s']:.1f} s more: "
              "once per install)")
    print("defect frequencies (Hz): " + ", ".join(
        f"{k} {v:.2f}" for k, v in freqs.as_dict().items()))
    if plot is not None:
        print(f"plot -> {plot}")
    return 0
