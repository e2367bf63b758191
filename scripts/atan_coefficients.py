"""Derives the arctangent's coefficients in src/core/simd_math.hpp and measures their error.

On |x| <= tan(pi/8) (z = x^2 <= 0.1716), atan(x) = x + x z g(z) with g(z) = (atan(x) - x)/(x z) = -1/3 + z/5 - ...
The model uses the [5/5] Pade approximant of g's Taylor series, scaled so that Q(0) = 1. This script prints P and Q
(lowest power first) and the largest relative error of x + x z P/Q against atan(x) on a fine grid, in 60-digit
arithmetic (mpmath, Debian's python3-mpmath), for the neighbouring orders too.

usage: /usr/bin/python3 scripts/atan_coefficients.py
"""
import mpmath as mp

mp.mp.dps = 60
taylor = [mp.mpf(-1) ** k / (2 * k + 1) for k in range(1, 30)]
z_max = mp.tan(mp.pi / 8) ** 2


def largest_relative_error(p, q, samples=2000):
    worst = mp.mpf(0)
    for i in range(1, samples + 1):
        z = z_max * i / samples
        x = mp.sqrt(z)
        approx = x + x * z * mp.polyval(p[::-1], z) / mp.polyval(q[::-1], z)
        worst = max(worst, abs(approx - mp.atan(x)) / mp.atan(x))
    return worst


for m, n in [(4, 4), (4, 5), (5, 5)]:
    p, q = mp.pade(taylor, m, n)
    p, q = [c / q[0] for c in p], [c / q[0] for c in q]
    print(f"[{m}/{n}] largest relative error on |x| <= tan(pi/8): {mp.nstr(largest_relative_error(p, q), 3)}")
    if (m, n) == (5, 5):
        print("  P:", ", ".join(mp.nstr(c, 20) for c in p))
        print("  Q:", ", ".join(mp.nstr(c, 20) for c in q))
print("pi/2 = hi + lo:", repr(float(mp.pi / 2)), mp.nstr(mp.pi / 2 - mp.mpf(float(mp.pi / 2)), 17))
print("pi/4 = hi + lo:", repr(float(mp.pi / 4)), mp.nstr(mp.pi / 4 - mp.mpf(float(mp.pi / 4)), 17))
