#!/usr/bin/python3
"""Draws docs/coupon_fit.png: a coupon test of the elastomer and the wall law's material fitted to it
(pf.fit_coupon, the same fit as finger_calibrate --coupon), Gent and Neo-Hookean, with each row's relative error.

    source devel/setup.bash; /usr/bin/python3 scripts/plot_coupon.py [--coupon data/epfl_ecoflex30_uniaxial.csv]
"""
import argparse
import os

from page_support import finish_axes, save

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--coupon", default=os.path.join(ROOT, "data", "epfl_ecoflex30_uniaxial.csv"))
    parser.add_argument("--output", default=os.path.join(ROOT, "docs", "coupon_fit.png"))
    args = parser.parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import pneumatic_finger.core as pf

    base = {"wall_law": "thick"}  # the material goes into a membrane or thick wall; the law only checks that
    fits = {law: pf.fit_coupon(args.coupon, law=law, overrides=base) for law in ("gent", "neo-hookean")}
    strain, stress = fits["gent"]["engineering_strain"], fits["gent"]["nominal_stress_pa"]
    fig, (ax, ax_error) = plt.subplots(2, 1, figsize=(7, 7), sharex=True, gridspec_kw={"height_ratios": [3, 1.3]})
    ax.plot(strain, stress / 1e3, ".", color="k", markersize=3, label="coupon test")
    for (law, fit), color in zip(fits.items(), ("C0", "C3")):
        mu, jm, preload = fit["shear_modulus_pa"], fit["wall_locking_jm"], fit["preload_strain"]
        name = (f"Gent: mu {mu / 1e3:.1f} kPa, J_m {jm:.0f}" if law == "gent" else f"Neo-Hookean: mu {mu / 1e3:.1f} kPa") \
            + f", preload {preload:.2f}"
        ax.plot(strain, fit["model_stress_pa"] / 1e3, "-", color=color, label=name)
        ax_error.plot(strain, 100 * (fit["model_stress_pa"] / stress - 1), "-", color=color)
    ax.set_ylabel("nominal stress (kPa)")
    finish_axes(ax, f"The elastomer from its coupon: {os.path.basename(args.coupon)}")
    ax_error.axhline(0, color="k", linewidth=0.8)
    ax_error.set_xlabel("engineering strain")
    ax_error.set_ylabel("fit - test (%)")
    ax_error.grid(alpha=0.3)
    save(fig, args.output)
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
