"""Derives the power series of stages 2-4 in src/core/wall_chain.hpp (stretchAndBulgeSeries, bulgeRootSeries) and
measures them.

With s = sqrt(g/3), the stretch excess delta (the root of delta^2 (3 + delta) = g (1 + delta), docs/MODEL.md stage 2)
and the bulge over the chamber height, h/L = (sqrt(1 + 4 delta + 2 delta^2) - 1)/2 (stage 3), are power series in s:
delta = s + s^2/3 - s^3/18 - ..., h/L = s - s^2/6 + 11 s^3/18 - ... Both are computed here exactly (rational
coefficients: the order-by-order solution of the cubic, then the series square root), printed as the doubles the code
holds (lowest power first), and checked: for every s up to the limit, the truncated series against the root itself in
50-digit arithmetic (mpmath), and the first left-out term against the limit.

h/L has a singularity at s = -0.35 (where 1 + 4 delta + 2 delta^2 = 0), so its coefficients grow like 2.85^k: at
s <= 1/20 the series needs terms to s^19 (delta, whose nearest singularity is farther, to s^13).

Stage 4 needs m = 2 sqrt(h c)/b; sqrt(h) = sqrt(L s) sqrt(h/(L s)), and sqrt(h/(L s)) = 1 - s/12 + ... is a series with
the same singularity (to s^18 in the code), so m needs no square root of h: only sqrt(s), which runs beside the series.

usage: /usr/bin/python3 scripts/wall_series.py
"""
from fractions import Fraction

import mpmath as mp

LIMIT = Fraction(1, 20)  # kStretchSeriesLimit in src/core/wall_chain.hpp
DELTA_TERMS = 13         # delta = s (c_0 + c_1 s + ... + c_12 s^12)
BULGE_TERMS = 19         # h/L = s (c_0 + ... + c_18 s^18)
ROOT_TERMS = 19          # sqrt(h/(L s)) = c_0 + ... + c_18 s^18
ORDER = 26               # series computed to s^26, to bound what is left out


def mul(a, b):
    n = min(len(a), len(b))
    out = [Fraction(0)] * n
    for i in range(n):
        if a[i]:
            for j in range(n - i):
                out[i + j] += a[i] * b[j]
    return out


def stretch_series():
    # delta^2 (3 + delta) - 3 s^2 (1 + delta) = 0: the coefficient of s^(k+1) holds a_k only through 6 a_1 a_k
    # (3 delta^2 with a_1 = 1), so a_k is the rest of that coefficient over -6.
    a = [Fraction(0), Fraction(1)] + [Fraction(0)] * ORDER  # to s^(ORDER + 1), which order ORDER's equation reaches
    for k in range(2, ORDER + 1):
        d2 = mul(a, a)
        lhs = [3 * x for x in d2]
        d3 = mul(d2, a)
        rest = lhs[k + 1] + d3[k + 1] - 3 * a[k - 1]  # -3 s^2 delta: a_(k-1); a_k itself is still 0 here
        a[k] = -rest / 6
    return a[:ORDER + 1]


def sqrt_series(x):
    # r^2 = x with x_0 = r_0 = 1: r_k = (x_k - sum_{0<i<k} r_i r_(k-i)) / 2.
    r = [Fraction(1)] + [Fraction(0)] * ORDER
    for k in range(1, ORDER + 1):
        r[k] = (x[k] - sum(r[i] * r[k - i] for i in range(1, k))) / 2
    return r


def bulge_series(a):
    x = [Fraction(0)] * (ORDER + 1)
    a2 = mul(a, a)
    for k in range(ORDER + 1):
        x[k] = 4 * a[k] + 2 * a2[k]
    x[0] += 1
    r = sqrt_series(x)
    return [(r[k] - (1 if k == 0 else 0)) / 2 for k in range(ORDER + 1)]


def main():
    mp.mp.dps = 50
    a = stretch_series()
    h = bulge_series(a)
    delta_c = [a[k] for k in range(1, DELTA_TERMS + 1)]
    bulge_c = [h[k] for k in range(1, BULGE_TERMS + 1)]
    root = sqrt_series([h[k + 1] for k in range(ORDER)] + [Fraction(0)])  # sqrt(h/(L s)), to s^(ORDER - 1)
    root_c = root[:ROOT_TERMS]
    print("kStretchSeries (delta / s, lowest power first):")
    print("  " + ", ".join(repr(float(c)) for c in delta_c))
    print("kBulgeSeries (h / (L s), lowest power first):")
    print("  " + ", ".join(repr(float(c)) for c in bulge_c))
    print("kBulgeRootSeries (sqrt(h / (L s)), lowest power first):")
    print("  " + ", ".join(repr(float(c)) for c in root_c))
    s_max = mp.mpf(LIMIT.numerator) / LIMIT.denominator
    root_shifted = [Fraction(0)] + root[:ORDER]  # as s sqrt(h/(L s)), so that the bound below reads alike
    for name, full, terms in (("delta", a, DELTA_TERMS), ("h/L", h, BULGE_TERMS),
                              ("sqrt(h/(L s))", root_shifted, ROOT_TERMS)):
        left_out = sum(abs(mp.mpf(full[k].numerator) / full[k].denominator) * s_max ** (k - 1)
                       for k in range(terms + 1, ORDER + 1))
        print(f"{name}: terms left out, relative, at s = {float(LIMIT)}: below {mp.nstr(left_out, 3)}")
    # The truncated series (exact coefficients rounded to doubles, summed in 50 digits) against the root itself.
    worst = {"delta": mp.mpf(0), "h/L": mp.mpf(0), "sqrt(h/(L s))": mp.mpf(0)}
    for i in range(1, 2001):
        s = s_max * i / 2000
        g = 3 * s * s
        root = mp.findroot(lambda d: d * d * (3 + d) - g * (1 + d), s)
        bulge = (mp.sqrt(1 + 4 * root + 2 * root * root) - 1) / 2
        got_d = s * mp.polyval([mp.mpf(float(c)) for c in reversed(delta_c)], s)
        got_h = s * mp.polyval([mp.mpf(float(c)) for c in reversed(bulge_c)], s)
        worst["delta"] = max(worst["delta"], abs(got_d - root) / root)
        worst["h/L"] = max(worst["h/L"], abs(got_h - bulge) / bulge)
        got_r = mp.polyval([mp.mpf(float(c)) for c in reversed(root_c)], s)
        worst["sqrt(h/(L s))"] = max(worst["sqrt(h/(L s))"], abs(got_r - mp.sqrt(bulge / s)) / mp.sqrt(bulge / s))
    for name, w in worst.items():
        print(f"{name}: largest relative error of the series with double coefficients on (0, {float(LIMIT)}]: "
              f"{mp.nstr(w, 3)}")


if __name__ == "__main__":
    main()
