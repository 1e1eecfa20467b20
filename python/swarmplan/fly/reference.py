"""The path an aircraft is asked to fly: the plan's flown path as time-stamped points.

Positions are linear between the points (the Rust model's flown path: straight pieces and
arcs densified into chords within the sagitta). The velocity feed-forward is the central
difference, smoothed over +-``v_smooth`` seconds by a centred triangular window: zero-phase,
so it does not bias a constant-curvature arc, while at a sharp corner (a level leg meeting
a 45 deg climb) it starts to turn ``v_smooth`` seconds early instead of asking for an
infinite acceleration (a 1 s window took the climbing corner's cross-track error from 4.8 to
1.5 m). The acceleration feed-forward is its derivative, capped in norm.

Frame: NED inside (north, east, down), as the autopilot works; the public inputs are the
scenario's x east, y north, z up.
"""

from typing import List, Sequence, Tuple

import numpy as np

Vec = List[float]


def _smooth(t: np.ndarray, v: np.ndarray, half_width: float) -> np.ndarray:
    """Centred triangular smoothing of each column of v(t), half-width in seconds."""
    h = 0.01
    grid = np.arange(t[0], t[-1] + h, h)
    nk = max(1, int(round(half_width / h)))
    kernel = np.concatenate([np.arange(1, nk + 1), np.arange(nk - 1, 0, -1)]).astype(float)
    kernel /= kernel.sum()
    out = np.empty_like(v)
    for i in range(v.shape[1]):
        vg = np.interp(grid, t, v[:, i])
        padded = np.concatenate([np.full(nk, vg[0]), vg, np.full(nk, vg[-1])])
        smooth = np.convolve(padded, kernel, mode="same")[nk:-nk]
        out[:, i] = np.interp(t, grid, smooth)
    return out


class Reference:
    """Position, velocity and acceleration along the points, by time or by nearest point."""

    def __init__(
        self,
        t: Sequence[float],
        x: Sequence[float],
        y: Sequence[float],
        z: Sequence[float],
        accel_cap: float,
        v_smooth: float,
    ) -> None:
        t = np.asarray(t, float)
        p = np.stack([np.asarray(y, float), np.asarray(x, float), -np.asarray(z, float)], axis=1)
        if len(t) >= 3:
            v = np.gradient(p, t, axis=0)
            if v_smooth > 0:
                v = _smooth(t, v, v_smooth)
            a = np.gradient(v, t, axis=0)
        elif len(t) == 2:
            v = np.repeat(((p[1] - p[0]) / max(t[1] - t[0], 1e-9))[None], 2, axis=0)
            a = np.zeros_like(p)
        else:
            v = np.zeros_like(p)
            a = np.zeros_like(p)
        norm = np.linalg.norm(a, axis=1)
        a = a * np.where(norm > accel_cap, accel_cap / np.maximum(norm, 1e-9), 1.0)[:, None]
        seg = np.diff(p, axis=0)
        lengths = np.linalg.norm(seg, axis=1)
        self.t = t.tolist()
        self.p = p.tolist()
        self.v = v.tolist()
        self.a = a.tolist()
        self.lengths = lengths.tolist()
        self.unit = (seg / np.maximum(lengths, 1e-9)[:, None]).tolist()
        self.arc = np.concatenate([[0.0], np.cumsum(lengths)]).tolist()
        self.is_path = len(t) >= 2
        self._k = 0  # segment of the planned time
        self._near = 0  # segment of the last nearest point

    def _segment_at(self, tau: float) -> int:
        t, k, n = self.t, self._k, len(self.t)
        while k < n - 2 and t[k + 1] <= tau:
            k += 1
        while k > 0 and t[k] > tau:
            k -= 1
        return k

    def at(self, tau: float) -> Tuple[Vec, Vec, Vec]:
        """Position, velocity and acceleration due at time tau (held at the ends)."""
        t, n = self.t, len(self.t)
        if n == 1 or tau <= t[0]:
            return self.p[0], [0.0] * 3, [0.0] * 3
        if tau >= t[-1]:
            return self.p[-1], [0.0] * 3, [0.0] * 3
        k = self._k = self._segment_at(tau)
        f = (tau - t[k]) / (t[k + 1] - t[k])
        return self._blend(k, f)

    def arc_at(self, tau: float) -> float:
        """Arc length due at time tau (after :meth:`at` for that tau)."""
        k = self._k
        t = self.t
        if tau <= t[0]:
            return 0.0
        if tau >= t[-1]:
            return self.arc[-1]
        return self.arc[k] + (tau - t[k]) / (t[k + 1] - t[k]) * self.lengths[k]

    def _blend(self, k: int, f: float) -> Tuple[Vec, Vec, Vec]:
        p0, p1 = self.p[k], self.p[k + 1]
        v0, v1 = self.v[k], self.v[k + 1]
        a0, a1 = self.a[k], self.a[k + 1]
        return (
            [p0[i] + f * (p1[i] - p0[i]) for i in range(3)],
            [v0[i] + f * (v1[i] - v0[i]) for i in range(3)],
            [a0[i] + f * (a1[i] - a0[i]) for i in range(3)],
        )

    def nearest(self, p: Vec, tau: float, ahead: float) -> Tuple[int, float]:
        """The nearest point of the path to p as (segment, fraction), searched from the last
        nearest segment (less two) to the segment due at tau + ahead, so it cannot jump to a
        far part of a path that comes back near itself."""
        t, n = self.t, len(self.t)
        hi = self._near
        while hi < n - 2 and t[hi + 1] <= tau + ahead:
            hi += 1
        best = (self._near, 0.0, float("inf"))
        for k in range(max(0, self._near - 2), hi + 1):
            a, u, length = self.p[k], self.unit[k], self.lengths[k]
            d0, d1, d2 = p[0] - a[0], p[1] - a[1], p[2] - a[2]
            f = min(max(d0 * u[0] + d1 * u[1] + d2 * u[2], 0.0), length)
            e0, e1, e2 = d0 - f * u[0], d1 - f * u[1], d2 - f * u[2]
            dd = e0 * e0 + e1 * e1 + e2 * e2
            if dd < best[2]:
                best = (k, f / length if length > 1e-9 else 0.0, dd)
        self._near = best[0]
        return best[0], best[1]

    def sample(self, k: int, f: float) -> Tuple[Vec, Vec, Vec, float]:
        """Position, velocity, acceleration and arc length at fraction f of segment k."""
        p, v, a = self._blend(k, f)
        return p, v, a, self.arc[k] + f * self.lengths[k]
