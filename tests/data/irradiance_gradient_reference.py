#!/usr/bin/env python3
"""References for the `irradiance` queries of tests/cli/cli_eval.sh, in 40-digit mpmath, sharing no
code or formula with daylit's kernels: Howell's configuration factor of a parallel rectangle
(DESIGN.md §7) summed over the corners about the foot point (exact for a uniform luminaire, also
when an occluder's straight shadow edge cuts it), differentiated numerically by mpmath.diff; and
for a linear exitance, 2-D Gauss–Legendre quadrature over the luminaire of M·K and M·∇_p K.
Run: python3 tests/data/irradiance_gradient_reference.py"""
from mpmath import mp, mpf, sqrt, atan, pi, diff, quad

mp.dps = 40


def howell(a, b, c):
    # Configuration factor from a point to the rectangle [0, a] × [0, b] at height c above it
    # (odd in a and in b, so corners combine with signs).
    A, B = a / c, b / c
    sa, sb = sqrt(1 + A * A), sqrt(1 + B * B)
    return (A / sa * atan(B / sa) + B / sb * atan(A / sb)) / (2 * pi)


def rectangle(p, x0, x1, y0, y1, z):
    px, py, pz = p
    c = z - pz
    return (howell(x1 - px, y1 - py, c) - howell(x0 - px, y1 - py, c) - howell(x1 - px, y0 - py, c)
            + howell(x0 - px, y0 - py, c))


def gradient(f, p):
    return [diff(lambda t: f([p[j] + (t if j == i else 0) for j in range(3)]), 0) for i in range(3)]


def show(name, f, p):
    print(name, mp.nstr(f(p), 17), [mp.nstr(g, 17) for g in gradient(f, p)])


M = mpf(2)
p = [mpf('0.3'), mpf('0.4'), mpf('0.2')]
# Uniform luminaire x ∈ [0, 1], y ∈ [0, 2] at z = 1.5, normal +z receiver.
show('uniform', lambda q: M * rectangle(q, 0, 1, 0, 2, mpf('1.5')), p)
# With an occluder: the plate x ≤ 0.5 at z = 0.75 (it covers the whole width in y): seen from q its
# edge falls on the luminaire's plane at x_s = q_x + (0.5 − q_x)(1.5 − q_z)/(0.75 − q_z).
def occluded(q):
    xs = q[0] + (mpf('0.5') - q[0]) * (mpf('1.5') - q[2]) / (mpf('0.75') - q[2])
    return M * rectangle(q, max(xs, 0), 1, 0, 2, mpf('1.5'))
show('occluded', occluded, p)


# Linear exitance M(x) = 1 + 0.5 x − 0.25 y on the same luminaire, by quadrature of the area form.
def linear_parts(q, i=None):
    def k(x, y):
        d = [x - q[0], y - q[1], mpf('1.5') - q[2]]
        r2 = d[0] ** 2 + d[1] ** 2 + d[2] ** 2
        nd = d[2]          # receiver normal +z
        cq = d[2]          # ν·(q − x) with ν = −z facing the receiver
        m = 1 + x / 2 - y / 4
        if i is None:
            return m * nd * cq / (pi * r2 * r2)
        n = [0, 0, 1]
        nu = [0, 0, -1]
        return m * ((nd * nu[i] - cq * n[i]) / (r2 * r2) + 4 * nd * cq * d[i] / (r2 ** 3)) / pi
    return quad(k, [0, 1], [0, 2])


print('linear', mp.nstr(linear_parts(p), 17), [mp.nstr(linear_parts(p, i), 17) for i in range(3)])
