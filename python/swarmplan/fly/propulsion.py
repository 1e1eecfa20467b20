"""The F450's rotors, inverted: the throttle that gives a wanted thrust.

JSBSim's F450 (``aircraft/F450`` in the ``jsbsim`` package) turns a throttle into motor
voltage, the Drela brushless-motor model into rotor speed, and the DJI 9450 propeller's
thrust and power coefficient tables C_T(J), C_P(J) into thrust. The autopilot asks for a
thrust; this module answers with the steady-state throttle that gives it for the axial
inflow the rotor sees, by inverting the same tables (values copied from the package's
``engine/DJI_9450.xml`` and ``engine/DJI_E305.xml``, and the airframe's mass and drag from
``aircraft/F450``). Checked against JSBSim in hover: throttle 0.411, 4946 rpm, 7.23 A,
the values JSBSim settles at.
"""

import math
from typing import List

import numpy as np

#: Take-off mass, kg (``Mass.xml``, empty weight).
MASS_KG = 1.4
#: Drag coefficient times reference area, m^2 (``Aero.xml`` x ``Metrics.xml``): the model's
#: only aerodynamics (no lift, no moments).
CD_S_M2 = 0.016129
#: Body rate per unit stick of the F450's rate SCAS, rad/s (``FlightControl.xml``).
SCAS_RATE = 0.75

PROP_D = 9.4 * 0.0254
_J = [0.0000, 0.0209, 0.0522, 0.0730, 0.1039, 0.1252, 0.1470, 0.1774,
      0.1983, 0.2287, 0.2504, 0.2774, 0.3022, 0.3235, 0.3539, 0.3757,
      0.4039, 0.4274, 0.4496, 0.4787, 0.5004, 0.5296, 0.5526, 0.5783,
      0.6039, 0.6257, 0.6548, 0.6774, 0.7039, 0.7291]
_CT = [0.1288, 0.1271, 0.1252, 0.1230, 0.1207, 0.1181, 0.1153, 0.1122,
       0.1089, 0.1053, 0.1015, 0.0975, 0.0932, 0.0888, 0.0842, 0.0794,
       0.0745, 0.0695, 0.0644, 0.0592, 0.0538, 0.0483, 0.0426, 0.0369,
       0.0310, 0.0250, 0.0189, 0.0128, 0.0064, -0.0001]
_CP = [0.0666, 0.0647, 0.0628, 0.0611, 0.0595, 0.0581, 0.0567, 0.0554,
       0.0542, 0.0531, 0.0520, 0.0509, 0.0498, 0.0485, 0.0471, 0.0456,
       0.0440, 0.0422, 0.0402, 0.0381, 0.0358, 0.0332, 0.0305, 0.0275,
       0.0243, 0.0210, 0.0175, 0.0137, 0.0099, 0.0061]
_KV = 960.0 * 2 * math.pi / 60.0  # rad/s per volt
_R_COIL = 0.117  # ohm
_I0 = 0.45  # A, no-load current
#: Battery voltage at full throttle, V.
VMAX = 14.63

_RHO0 = 1.225
_THRUSTS = np.linspace(0.0, 12.0, 61)  # N per rotor
_INFLOWS = np.linspace(-20.0, 40.0, 61)  # m/s, axial


def _steady_volts(n, v_axial, rho):
    """Motor voltage that holds n rev/s with axial inflow v_axial (vectorised)."""
    cp = np.interp(v_axial / (n * PROP_D), _J, _CP)
    omega = 2 * np.pi * n
    torque = cp * rho * n ** 3 * PROP_D ** 5 / omega
    return omega / _KV + _R_COIL * (torque * _KV + _I0)


def _thrust(n, v_axial, rho):
    return np.interp(v_axial / (n * PROP_D), _J, _CT) * rho * n * n * PROP_D ** 4


def _throttle_table() -> List[List[float]]:
    """Throttle over (thrust, inflow) at sea-level density: rotor speed by bisection (the
    thrust grows with it at a given inflow), then the voltage that holds it."""
    t, v = np.meshgrid(_THRUSTS, _INFLOWS, indexing="ij")
    lo = np.full(t.shape, 1.0)
    hi = np.full(t.shape, 1000.0)
    for _ in range(50):
        mid = 0.5 * (lo + hi)
        enough = _thrust(mid, v, _RHO0) >= t
        hi = np.where(enough, mid, hi)
        lo = np.where(enough, lo, mid)
    return (_steady_volts(hi, v, _RHO0) / VMAX).tolist()


_TABLE = _throttle_table()


def throttle_for_thrust(thrust_n: float, v_axial: float, rho: float) -> float:
    """Throttle giving ``thrust_n`` newtons on one rotor with axial inflow ``v_axial`` m/s
    (positive: air entering from above, as when climbing) at density ``rho`` kg/m^3; above 1
    means out of reach. Bilinear in the table; thrust scales with density (C_T rho n^2)."""
    t = thrust_n * _RHO0 / rho
    dt, dv = _THRUSTS[1] - _THRUSTS[0], _INFLOWS[1] - _INFLOWS[0]
    fi = min(max((t - _THRUSTS[0]) / dt, 0.0), len(_THRUSTS) - 1.001)
    fj = min(max((v_axial - _INFLOWS[0]) / dv, 0.0), len(_INFLOWS) - 1.001)
    i, j = int(fi), int(fj)
    a, b = fi - i, fj - j
    m0, m1 = _TABLE[i], _TABLE[i + 1]
    return (1 - a) * ((1 - b) * m0[j] + b * m0[j + 1]) + a * ((1 - b) * m1[j] + b * m1[j + 1])
