"""A computation of the notch impact independent of the multibody model, for
benchmarks/seed000.py: closed forms and a reduced model solved by scipy.

The reduced model keeps only what decides the impact of one ball at a notch: the inner
race (mass ``m_ring``, x and y) carried by the other balls (massless, Hertz series
contacts, orbiting at the cage speed), and the ball that meets the notch (mass, radial
coordinate between its inner and outer contact, centrifugal force and weight), with the
notch profile of the trailing corner (the mating surface sinks until it meets the
nearer corner, ``R - sqrt(R^2 - a^2)``, at most the depth), carried past the contact at
the rolling speed. Kramer's damping ``tau dQ/d(delta) d(delta)/dt`` on every contact. It
shares no code with ballpass.simulate.multibody: its own equations, scipy's LSODA at
rtol 1e-9, Hertz constants from :meth:`ballpass.Bearing.contact_stiffnesses`.

The housing acceleration is the force the balls put on the outer race through a 1 kg
housing on 4e10 N/m (Nakhaeinejad & Bryant's Table 1 stiffness) and the sensor's 15 kHz
resonance, then the 8-30 kHz band, like the multibody page's figures.
"""

from __future__ import annotations

import math

import numpy as np
from scipy import integrate, optimize, signal

from ballpass.bearing import series_stiffness

G = 9.80665
DENSITY = 7750.0  # kg/m^3, Nakhaeinejad & Bryant Table 1
#: the faulty ball's angle from the load line at the start of a passage (the
#: multibody's first load-zone passage of an inner-race notch at 330 deg), rad
PSI_START = math.radians(18.0)


def _hertz(k, d, dd, tau):
    """Hertz force with Kramer damping on the linearised stiffness, never pulling."""
    if d <= 0.0:
        return 0.0
    return max(0.0, k * d ** 1.5 + tau * 1.5 * k * math.sqrt(d) * dd)


def kinematics(bearing, rpm, kind):
    """(relative radius R of the notch and the ball, m; speed at which the notch passes
    the contact, m/s; ball mass, kg; centrifugal force, N) for a notch on the ``kind``
    race. The ball's own notch meets the race at the same speed (rolling without slip):
    at the inner contact it pairs like an inner-race notch, at the outer like an
    outer-race one."""
    rb = 0.5 * bearing.element_diameter_m
    ri, ro = bearing.inner_race_radius_m, bearing.outer_race_radius_m
    wi = rpm * math.pi / 30.0
    om = wi * ri / (ri + ro)
    mb = DENSITY * math.pi / 6.0 * bearing.element_diameter_m ** 3
    if kind == "inner":
        return 1.0 / (1.0 / rb + 1.0 / ri), (wi - om) * ri, mb, mb * om * om * (ri + rb)
    return 1.0 / (1.0 / rb - 1.0 / ro), om * ro, mb, mb * om * om * (ri + rb)


def closed_form(bearing, rpm, load_q, kind, width, depth, psi=0.0):
    """The trailing corner's closing speed on a ball that has spent the notch's passage
    time t = w / u in it, for a ball loaded with ``load_q`` N before the notch.

    Outer race: the ball, freed from its outer contact, falls into the notch under its
    centrifugal force and weight, s = a t^2 / 2 with a = (F_c + m g cos psi) / m, at
    most the corner-limited depth R - sqrt(R^2 - w^2/4) (and the depth h); the corner
    meets it where the profile has risen back to s, with the slope sqrt(2 R s) / R:
    v = u sqrt(2 s / R) + a t. Inner race: the same forces push the ball away from the
    notch, so it waits on the outer race (s = 0); the corner comes back up by the
    approach the ball had before the notch (the Hertz approaches of both contacts,
    g = (Q / K_i)^(2/3) + (Q / K_o)^(2/3)): v = u sqrt(2 g / R), independent of the
    width and the depth once the notch is wider than 2 sqrt(2 R g) and deeper than g
    (the inner race's own motion neglected).

    Returns
    -------
    dict
        ``speed`` closing speed, m/s; ``u`` rolling speed, m/s; ``t`` passage time, s;
        ``acc`` outward acceleration of the free ball, m/s^2; ``drop`` s, m; ``gap`` g,
        m (inner); ``reff`` R, m; ``min_width`` 2 sqrt(2 R g), m (inner).
    """
    reff, u, mb, fc = kinematics(bearing, rpm, kind)
    t_w = width / u
    acc = (fc + mb * G * math.cos(psi)) / mb
    out = {"u": u, "t": t_w, "acc": acc, "reff": reff, "gap": 0.0, "min_width": 0.0}
    if kind == "outer":
        a = min(0.5 * width, reff)
        out["drop"] = min(0.5 * acc * t_w * t_w, reff - math.sqrt(reff * reff - a * a), depth)
        out["speed"] = u * math.sqrt(2.0 * out["drop"] / reff) + acc * t_w
        return out
    ki, ko = bearing.contact_stiffnesses()
    gap = (load_q / ki) ** (2.0 / 3.0) + (load_q / ko) ** (2.0 / 3.0)
    out.update(drop=0.0, gap=gap, min_width=2.0 * math.sqrt(2.0 * reff * gap),
               speed=u * math.sqrt(2.0 * min(gap, depth) / reff))
    return out


def reduced_impact(bearing, rpm, radial_load, kind, width, depth, *, m_ring=1.0,
                   tau=1e-5, psi=PSI_START, fs_out=2e6, resonance_hz=15e3,
                   zeta=0.05):
    """Simulate one load-zone passage of a notch with the reduced model.

    Parameters
    ----------
    bearing : ballpass.Bearing
        Zero clearance is assumed.
    rpm, radial_load : float
        Shaft speed (rpm) and radial load on the inner race (N).
    kind : {"inner", "outer"}
        Which race carries the notch (a ball's notch pairs like the race it meets).
    width, depth : float
        Notch size, m.
    m_ring : float
        Inner race (with the shaft share), kg.
    tau : float
        Kramer's damping time, s (1e-5 Kramer; 1e-2 as printed in the paper's eq. 9).
    psi : float
        Angle of the faulty ball from the load line at the start, rad.

    Returns
    -------
    dict
        ``peak``: largest 8-30 kHz housing acceleration, m/s^2; ``q_peak``: largest
        inner contact force of the faulty ball, N; ``ball_drop``: how far the ball
        moved outwards beyond its start, m; ``t``, ``accel`` the band signal.
    """
    z = bearing.n_elements
    ki, ko = bearing.contact_stiffnesses()
    ks = series_stiffness(ki, ko, 1.5)
    reff, u, mb, fc = kinematics(bearing, rpm, kind)
    om = rpm * math.pi / 30.0 * bearing.inner_race_radius_m / (
        bearing.inner_race_radius_m + bearing.outer_race_radius_m)
    load = radial_load + m_ring * G
    s0 = -0.5 * width - 0.25e-3       # the notch's centre 0.25 mm short of its edge

    def drop(t):
        a = 0.5 * width - abs(s0 + u * t)
        if a <= 0.0:
            return 0.0
        return min(depth, reff - math.sqrt(max(reff * reff - a * a, 0.0)))

    others = 2.0 * math.pi * np.arange(1, z) / z

    def forces(t, y):
        x, yy, r, vx, vy, vr = y
        c, s = np.cos(psi + om * t + others), np.sin(psi + om * t + others)
        q = np.array([_hertz(ks, d, dd, tau)
                      for d, dd in zip(x * c + yy * s, vx * c + vy * s, strict=True)])
        cf, sf = math.cos(psi + om * t), math.sin(psi + om * t)
        di, do = x * cf + yy * sf - r, r
        if kind == "inner":
            di -= drop(t)
        else:
            do -= drop(t)
        qi = _hertz(ki, di, vx * cf + vy * sf - vr, tau)
        qo = _hertz(ko, do, vr, tau)
        return q, c, s, cf, sf, qi, qo

    def rhs(t, y):
        q, c, s, cf, sf, qi, qo = forces(t, y)
        return [y[3], y[4], y[5], (load - (q * c).sum() - qi * cf) / m_ring,
                (-(q * s).sum() - qi * sf) / m_ring, (qi - qo + fc + mb * G * cf) / mb]

    def residual(v):
        d = rhs(0.0, [v[0], v[1], v[2], 0.0, 0.0, 0.0])
        return [d[3] * m_ring / load, d[4] * m_ring / load, d[5] * mb / load]

    start = optimize.root(residual, [3e-6, 0.0, 1e-6], method="hybr", tol=1e-15).x
    t_end = (width + 0.5e-3) / u + 1.5e-3
    sol = integrate.solve_ivp(rhs, (0.0, t_end), [*start, 0.0, 0.0, 0.0], method="LSODA",
                              rtol=1e-9, atol=1e-13, max_step=0.5e-6, dense_output=True)
    t = np.arange(0.0, t_end, 1.0 / fs_out)
    ys = sol.sol(t)
    f_out = np.empty(t.size)
    q_in = np.empty(t.size)
    for k in range(t.size):
        q, c, _s, cf, _sf, qi, qo = forces(t[k], ys[:, k])
        f_out[k] = (q * c).sum() + qo * cf
        q_in[k] = qi
    # housing (1 kg on 4e10 N/m, damping tau k) then the sensor resonance
    wh, wn = math.sqrt(4e10), 2.0 * math.pi * resonance_hz
    housing = ([1.0, 0.0, 0.0], [1.0, 1e-5 * wh * wh, wh * wh])
    sensor = ([2.0 * zeta * wn, wn * wn], [1.0, 2.0 * zeta * wn, wn * wn])
    acc = f_out - f_out[0]
    for num, den in (housing, sensor):
        b, a, _ = signal.cont2discrete((num, den), 1.0 / fs_out, method="bilinear")
        acc = signal.lfilter(np.ravel(b), a, acc)
    sos = signal.butter(4, (8000.0, 30000.0), "bandpass", fs=fs_out, output="sos")
    band = signal.sosfiltfilt(sos, acc)
    return {"peak": float(np.abs(band).max()), "q_peak": float(q_in.max()),
            "ball_drop": float(ys[2].max() - start[2]), "t": t, "accel": band}
