"""coulomb_ref.py - the library's coulomb block (a mass m with dry friction Fc sliding,
Fs static) under F = A sin(w t), independently of modrt: piecewise closed forms (sliding
with mode s, v and x are integrals of (A sin w t - s Fc) / m; stuck, nothing moves), the
switches found by a scan of 1e-4 s and 100 bisections. Used by tests/hard/cases_events.py;
`python3 coulomb_ref.py` prints the state at 3 s of the default case."""
import math


def _bisect(fn, a, b):
    fa = fn(a)
    for _ in range(100):
        c = 0.5 * (a + b)
        fc = fn(c)
        if (fc > 0) == (fa > 0):
            a, fa = c, fc
        else:
            b = c
    return 0.5 * (a + b)


def _first(fn, t, t_end, dt=1e-4):
    """the first time after t where fn turns positive (scanned, then bisected), or None"""
    s = t
    while s < t_end:
        if fn(min(s + dt, t_end)) > 0:
            return _bisect(fn, s, min(s + dt, t_end))
        s += dt
    return None


def state(t_end, A=5.0, w=2 * math.pi, m=1.0, Fc=2.0, Fs=3.0, x=0.0, v=0.0, mode=0):
    """(x, v, mode, switch times) at t_end from the given start"""
    F = lambda u: A * math.sin(w * u)
    t, switches = 0.0, []
    while t < t_end:
        if mode == 0:
            tb = _first(lambda u: abs(F(u)) - Fs, t + 1e-12, t_end)
            if tb is None:
                break
            t, mode = tb, (1 if F(tb) > 0 else -1)
            switches.append(t)
            continue
        t0, x0, v0, s = t, x, v, mode
        V = lambda u: v0 + (A / w * (math.cos(w * t0) - math.cos(w * u)) - s * Fc * (u - t0)) / m
        X = lambda u: x0 + v0 * (u - t0) + (A / w * (math.cos(w * t0) * (u - t0)
                      - (math.sin(w * u) - math.sin(w * t0)) / w) - s * Fc * (u - t0) ** 2 / 2) / m
        ts = _first(lambda u: -s * V(u), t0 + 1e-9, t_end)
        if ts is None:
            return X(t_end), V(t_end), mode, switches
        x, v, t = X(ts), 0.0, ts
        switches.append(t)
        mode = (1 if F(t) > 0 else -1) if abs(F(t)) > Fs else 0
    return x, v, mode, switches


if __name__ == "__main__":
    print(state(3.0))
