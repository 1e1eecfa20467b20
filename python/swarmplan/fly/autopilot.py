"""An autopilot for JSBSim's F450 quadrotor that flies a time-stamped path.

The F450 ships with a rate-command flight control system (SCAS) and no position or velocity
loop; this is the cascade above it, run every JSBSim step (or every ``ctrl_every``-th):

1. **Path** (outer loop). After the hover, the nearest point q of the path (searched near
   the planned time, :meth:`Reference.nearest`) gives the cross-track error; the commanded
   velocity is the path's velocity at q, plus ``KP_X`` times the error towards q (capped at
   ``VCORR_X``), plus ``KP_A`` times the along-track timing error (capped at ``VCORR_A``)
   along the path. Cross-track has priority: a lag after the hover (0 to 15 m/s takes at
   least 11 m even at 1 g) is caught up along the path, not by cutting across it. Steering
   to the point due at the planned time instead gave 8.8 m cross-track on a circle entered
   from a hover, against 0.9 m. In the hover: position hold (``KP_H``, ``KP_V``).
2. **Velocity**: PI with the path's acceleration as feed-forward, horizontal and vertical
   gains apart; the integrators are clamped (``I_MAX_H``, ``I_MAX_V``) and stop while the
   tilt or the thrust is saturated (conditional integration: no wind-up).
3. **Thrust vector**: m (a - g) plus the airframe's drag at the air-relative velocity; thrust
   limited to [``T_MIN``, ``T_MAX``] x weight with the vertical part first, tilt to
   ``TILT_MAX``. Its direction gives roll and pitch at a constant heading (a quadrotor need
   not turn its nose); its size along the body axis gives the throttle
   (:func:`propulsion.throttle_for_thrust`).
4. **Attitude**: ``K_ATT`` on the roll and pitch errors, ``K_PSI`` on heading, turned into
   body rates and sent to the SCAS as ``fcs/aileron-cmd-norm``, ``fcs/elevator-cmd-norm``,
   ``fcs/rudder-cmd-norm`` (body rate / 0.75 rad/s) with ``fcs/throttle-cmd-norm``.

Gains were tuned by hand on a straight line, a 50 m circle, a 90 deg corner of 50 m radius
and 45 deg climbs and dives at 15 m/s, calm, keeping each loop 3-5 times slower than the
one inside it: the SCAS rate loop settles in about 0.05 s, attitude 1 / K_ATT = 0.14 s,
velocity 1 / KV about 0.4 s, path 1 / KP_X about 0.8 s (docs/flight.md has the table).
JSBSim must step at 1/120 s or faster: the F450's own rate loop is unstable at 1/60 s and
marginal at 1/90 s.

Frame: a flat earth around (``lat0``, ``lon0``) (WGS 84 meridian and prime-vertical radii),
x east, y north; altitude is JSBSim's height above sea level, the terrain elevation under
the aircraft set to 0 (the scenario's terrain is judged afterwards, not simulated).
"""

import contextlib
import math
import os
import sys
import time
from typing import Any, Dict, Iterator, Optional, Sequence, Tuple

import numpy as np

from .propulsion import CD_S_M2, MASS_KG, SCAS_RATE, VMAX, throttle_for_thrust
from .reference import Reference

FT = 0.3048
G0 = 9.80665
SLUG_FT3 = 515.378818

#: The cascade's gains (module doc); ``fly_path(..., gains={...})`` overrides any.
GAINS: Dict[str, float] = dict(
    KP_H=1.0,  # 1/s, hover: horizontal position error -> velocity
    KP_V=1.2,  # 1/s, vertical position error -> velocity
    VCORR_H=5.0,  # m/s, cap of the horizontal position correction
    VCORR_V=3.0,  # m/s, cap of the vertical position correction
    AHEAD=1.0,  # s, nearest-point search window past the planned time
    V_SMOOTH=1.0,  # s, half-width of the velocity feed-forward's smoothing
    KP_X=1.2,  # 1/s, cross-track error -> velocity
    VCORR_X=5.0,  # m/s, cap of the cross-track correction
    KP_A=0.6,  # 1/s, along-track timing error -> speed
    VCORR_A=4.0,  # m/s, cap of the along-track correction
    KV_H=2.5,  # 1/s, horizontal velocity error -> acceleration
    KV_V=3.0,  # 1/s, vertical velocity error -> acceleration
    KI_H=0.8,  # 1/s^2, horizontal velocity integrator
    KI_V=1.5,  # 1/s^2, vertical velocity integrator
    I_MAX_H=3.0,  # m/s^2, horizontal integrator clamp
    I_MAX_V=4.0,  # m/s^2, vertical integrator clamp
    A_FF_MAX=8.0,  # m/s^2, cap of the acceleration feed-forward
    TILT_MAX=math.radians(45.0),  # rad
    K_ATT=7.0,  # 1/s, roll and pitch error -> Euler rate
    K_PSI=2.0,  # 1/s, heading error -> yaw rate
    T_MIN=0.15,  # x weight
    T_MAX=2.0,  # x weight
)

#: JSBSim's turbulence settings by name: MIL-F-8785C Dryden (``atmosphere/turb-type`` 3)
#: with the wind speed at 20 ft and the severity it takes.
TURBULENCE = {"light": 2, "moderate": 3, "severe": 5}

_A = 6378137.0
_E2 = 6.69437999014e-3


def _radii(lat0: float) -> Tuple[float, float]:
    """Metres per radian of latitude and of longitude at latitude lat0 (degrees)."""
    s = math.sin(math.radians(lat0))
    w = 1.0 - _E2 * s * s
    return _A * (1.0 - _E2) / w ** 1.5, _A / math.sqrt(w) * math.cos(math.radians(lat0))


@contextlib.contextmanager
def _quiet() -> Iterator[None]:
    """JSBSim prints its banner and the F450's configuration warnings from C++ on the
    process's standard output: sent to /dev/null while it loads."""
    sys.stdout.flush()
    saved = os.dup(1)
    null = os.open(os.devnull, os.O_WRONLY)
    os.dup2(null, 1)
    try:
        yield
    finally:
        sys.stdout.flush()
        os.dup2(saved, 1)
        os.close(saved)
        os.close(null)


def _fdm(
    x0: float, y0: float, z0: float, dt: float, lat0: float, lon0: float, v0: Sequence[float]
) -> Any:
    import jsbsim

    m, n = _radii(lat0)
    with _quiet():
        fdm = jsbsim.FGFDMExec(jsbsim.get_default_root_dir())
        fdm.set_debug_level(0)
        fdm.load_model("F450")
        fdm.set_dt(dt)
        fdm["ic/terrain-elevation-ft"] = 0.0
        fdm["ic/lat-geod-deg"] = lat0 + math.degrees(y0 / m)
        fdm["ic/long-gc-deg"] = lon0 + math.degrees(x0 / n)
        fdm["ic/h-sl-ft"] = z0 / FT
        for name in ("ic/psi-true-deg", "ic/phi-deg", "ic/theta-deg"):
            fdm[name] = 0.0
        for name, v in zip(("ic/vn-fps", "ic/ve-fps", "ic/vd-fps"), v0):
            fdm[name] = v / FT
        fdm.run_ic()
    fdm["fcs/ScasEngage"] = 1.0
    return fdm


def fly_path(
    t: Sequence[float],
    x: Sequence[float],
    y: Sequence[float],
    z: Sequence[float],
    *,
    hover: float = 0.0,
    wind: Tuple[float, float] = (0.0, 0.0),
    turbulence: Optional[str] = None,
    seed: int = 0,
    dt: float = 1.0 / 120,
    ctrl_every: int = 1,
    record_every: int = 12,
    gains: Optional[Dict[str, float]] = None,
    lat0: float = 0.0,
    lon0: float = 0.0,
) -> Dict[str, Any]:
    """Flies the F450 from the first point, hovering there for ``hover`` seconds, then
    along (t, x, y, z) (x east, y north, z altitude, metres; t seconds), on the clock of t:
    simulation time s is path time t[0] - hover + s.

    ``wind`` is the air mass's velocity (east, north) in m/s; ``turbulence`` None (calm) or
    a key of :data:`TURBULENCE` (Dryden, JSBSim's random seed ``seed``). Returns the flown
    ``t`` (path clock), ``x``, ``y``, ``z`` every ``record_every`` steps, ``energy_j``
    (electrical: the sum over the four motors of voltage x current, from JSBSim's motor
    model), ``crashed`` and ``reason`` (NaN, below the datum, or 100 m off the path), and
    ``wall_s``.
    """
    wall0 = time.perf_counter()
    if dt > 1.0 / 120 + 1e-12:
        raise ValueError(f"dt: expected at most 1/120 s (the F450's rate loop), got {dt}")
    g = dict(GAINS)
    g.update(gains or {})
    ref = Reference(t, x, y, z, g["A_FF_MAX"], g["V_SMOOTH"])
    t0 = float(ref.t[0])
    steps = int(round((hover + ref.t[-1] - t0) / dt))
    # Without a hover the model flies off at its speed from t[0] (it has no take-off
    # phase): the aircraft starts there already moving at the path's velocity. After a
    # hover it must accelerate, and lags behind the schedule until it has caught up.
    v0 = ref.v[0] if hover <= 0.0 else (0.0, 0.0, 0.0)
    fdm = _fdm(float(x[0]), float(y[0]), float(z[0]), dt, lat0, lon0, v0)
    m_rad, n_rad = _radii(lat0)
    fdm["atmosphere/wind-north-fps"] = wind[1] / FT
    fdm["atmosphere/wind-east-fps"] = wind[0] / FT
    fdm["atmosphere/wind-down-fps"] = 0.0
    if turbulence is not None:
        if turbulence not in TURBULENCE:
            raise ValueError(
                f"turbulence: expected one of {sorted(TURBULENCE)} or None, got {turbulence!r}"
            )
        fdm["simulation/randomseed"] = int(seed)
        fdm["atmosphere/turb-type"] = 3
        speed = math.hypot(wind[0], wind[1])
        fdm["atmosphere/turbulence/milspec/windspeed_at_20ft_AGL-fps"] = max(speed, 1.0) / FT
        fdm["atmosphere/turbulence/milspec/severity"] = TURBULENCE[turbulence]
        fdm["atmosphere/psiw-rad"] = math.atan2(wind[0], wind[1])
    state = _Cascade(g, fdm["attitude/psi-rad"])
    get = fdm.get_property_value
    throttles = [f"fcs/throttle-pos-norm[{i}]" for i in range(4)]
    currents = [f"propulsion/engine[{i}]/current-amperes" for i in range(4)]
    d2r = math.pi / 180.0
    out_t, out_p = [], []
    energy = 0.0
    crashed, reason = False, ""
    for k in range(steps + 1):
        s = k * dt
        tau = t0 - hover + s
        pn = (get("position/lat-geod-deg") - lat0) * d2r * m_rad
        pe = (get("position/long-gc-deg") - lon0) * d2r * n_rad
        pd = -get("position/h-sl-meters")
        for i in range(4):
            energy += max(0.0, VMAX * get(throttles[i]) * get(currents[i])) * dt
        if k % record_every == 0 or k == steps:
            out_t.append(tau)
            out_p.append((pe, pn, -pd))
        due = ref.p[0] if s < hover else ref.at(tau)[0]
        off = math.dist(due, (pn, pe, pd))
        if off != off or -pd < 0.5 or off > 100.0:
            crashed = True
            reason = "NaN state" if off != off else ("below the datum" if -pd < 0.5 else "100 m off the path")
            break
        if k == steps:
            break
        if k % ctrl_every == 0:
            state.step(fdm, ref, (pn, pe, pd), s < hover, tau, dt * ctrl_every)
        fdm.run()
    flown = np.asarray(out_p, float).reshape(-1, 3)
    return dict(
        t=np.asarray(out_t, float),
        x=flown[:, 0],
        y=flown[:, 1],
        z=flown[:, 2],
        energy_j=energy,
        crashed=crashed,
        reason=reason,
        wall_s=time.perf_counter() - wall0,
    )


class _Cascade:
    """The loops' state: integrators, saturation flags and the heading held."""

    def __init__(self, gains: Dict[str, float], heading: float) -> None:
        self.g = gains
        self.heading = heading
        self.i_h = [0.0, 0.0]
        self.i_v = 0.0
        self.sat_h = False
        self.sat_v = False

    def _velocity_command(self, ref: Reference, pos, hovering: bool, tau: float):
        g = self.g
        if not hovering and tau < ref.t[-1] and ref.is_path:
            k, f = ref.nearest(pos, tau, g["AHEAD"])
            pq, vq, aq, sq = ref.sample(k, f)
            ref.at(tau)
            lag = ref.arc_at(tau) - sq
            along = max(-g["VCORR_A"], min(g["VCORR_A"], g["KP_A"] * lag))
            e = [pq[i] - pos[i] for i in range(3)]
            size = g["KP_X"] * math.sqrt(e[0] ** 2 + e[1] ** 2 + e[2] ** 2)
            gain = g["KP_X"] if size <= g["VCORR_X"] else g["KP_X"] * g["VCORR_X"] / size
            u = ref.unit[k]
            return [vq[i] + along * u[i] + gain * e[i] for i in range(3)], aq
        p, v, a = (ref.p[0], [0.0] * 3, [0.0] * 3) if hovering else ref.at(tau)
        cn, ce = g["KP_H"] * (p[0] - pos[0]), g["KP_H"] * (p[1] - pos[1])
        cm = math.hypot(cn, ce)
        if cm > g["VCORR_H"]:
            cn, ce = cn * g["VCORR_H"] / cm, ce * g["VCORR_H"] / cm
        cd = max(-g["VCORR_V"], min(g["VCORR_V"], g["KP_V"] * (p[2] - pos[2])))
        return [v[0] + cn, v[1] + ce, v[2] + cd], a

    def step(self, fdm: Any, ref: Reference, pos, hovering: bool, tau: float, cdt: float) -> None:
        g = self.g
        get = fdm.get_property_value
        vel = [get(f"velocities/v-{d}-fps") * FT for d in ("north", "east", "down")]
        phi, th, psi = (get(f"attitude/{a}-rad") for a in ("phi", "theta", "psi"))
        v_cmd, a_ff = self._velocity_command(ref, pos, hovering, tau)
        ev = [v_cmd[i] - vel[i] for i in range(3)]
        if not self.sat_h:
            self.i_h = [self.i_h[0] + g["KI_H"] * ev[0] * cdt, self.i_h[1] + g["KI_H"] * ev[1] * cdt]
            im = math.hypot(*self.i_h)
            if im > g["I_MAX_H"]:
                self.i_h = [c * g["I_MAX_H"] / im for c in self.i_h]
        if not self.sat_v:
            self.i_v = max(-g["I_MAX_V"], min(g["I_MAX_V"], self.i_v + g["KI_V"] * ev[2] * cdt))
        acc = [
            a_ff[0] + g["KV_H"] * ev[0] + self.i_h[0],
            a_ff[1] + g["KV_H"] * ev[1] + self.i_h[1],
            a_ff[2] + g["KV_V"] * ev[2] + self.i_v,
        ]
        cph, sph, cth, sth = math.cos(phi), math.sin(phi), math.cos(th), math.sin(th)
        cps, sps = math.cos(psi), math.sin(psi)
        ua, va, wa = (get(f"velocities/{c}-aero-fps") * FT for c in ("u", "v", "w"))
        air = (
            cth * cps * ua + (sph * sth * cps - cph * sps) * va + (cph * sth * cps + sph * sps) * wa,
            cth * sps * ua + (sph * sth * sps + cph * cps) * va + (cph * sth * sps - sph * cps) * wa,
            -sth * ua + sph * cth * va + cph * cth * wa,
        )
        rho = get("atmosphere/rho-slugs_ft3") * SLUG_FT3
        drag = 0.5 * rho * CD_S_M2 * math.sqrt(sum(c * c for c in air))
        fn = MASS_KG * acc[0] + drag * air[0]
        fe = MASS_KG * acc[1] + drag * air[1]
        fd = MASS_KG * (acc[2] - G0) + drag * air[2]
        weight = MASS_KG * G0
        t_min, t_max = g["T_MIN"] * weight, g["T_MAX"] * weight
        up = max(t_min, min(t_max, -fd))
        self.sat_v = (-fd > t_max and ev[2] < 0) or (-fd < t_min and ev[2] > 0)
        fh = math.hypot(fn, fe)
        fh_max = min(up * math.tan(g["TILT_MAX"]), math.sqrt(max(t_max * t_max - up * up, 0.0)))
        self.sat_h = fh > fh_max
        if self.sat_h:
            fn, fe = fn * fh_max / fh, fe * fh_max / fh
        fd = -up
        total = math.sqrt(fn * fn + fe * fe + fd * fd)
        un, ue, ud = fn / total, fe / total, fd / total
        forward = cps * un + sps * ue
        right = -sps * un + cps * ue
        phi_c = math.asin(max(-1.0, min(1.0, right)))
        th_c = math.atan2(-forward, -ud)
        phid = g["K_ATT"] * (phi_c - phi)
        thd = g["K_ATT"] * (th_c - th)
        psid = g["K_PSI"] * ((self.heading - psi + math.pi) % (2 * math.pi) - math.pi)
        rates = (
            phid - sth * psid,
            cph * thd + sph * cth * psid,
            -sph * thd + cph * cth * psid,
        )
        setp = fdm.set_property_value
        for name, rate in zip(("aileron", "elevator", "rudder"), rates):
            setp(f"fcs/{name}-cmd-norm", max(-1.0, min(1.0, rate / SCAS_RATE)))
        axis = (-(cph * sth * cps + sph * sps), -(cph * sth * sps - sph * cps), -(cph * cth))
        along_axis = max(t_min, fn * axis[0] + fe * axis[1] + fd * axis[2])
        setp("fcs/throttle-cmd-norm", max(0.0, min(1.0, throttle_for_thrust(along_axis / 4.0, -wa, rho))))
