#!/usr/bin/python3
"""The README's picture (docs/img/sliding_contact.png): what rhabel solves, drawn from a solve of
the README's example scene (examples/snippets/scene.json) with the Python package.

    PYTHONPATH=build/python /usr/bin/python3 scripts/plot_readme_figure.py [OUT.png]

Top row: each indentor (grey) on the deformed surface of the half-space (the surface displacement
of the solution, in micrometres against millimetres: vertical scale exaggerated), sliding towards -x; bottom row: the contact pressure,
with the edge exponents of the result. Nothing is computed here but the drawing.
Uses matplotlib (Debian: python3-matplotlib).
"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import rhabel


def main(out="docs/img/sliding_contact.png"):
    scene = rhabel.load_scene("examples/snippets/scene.json")
    r = rhabel.solve(scene, grid=801)
    m = scene["material"]
    fig, axes = plt.subplots(2, len(r.indentors), figsize=(10, 5.2), sharex="col",
                             gridspec_kw={"height_ratios": [1.1, 1]})
    for j, (ind, spec) in enumerate(zip(r.indentors, scene["indentors"])):
        top, bot = axes[0][j], axes[1][j]
        a, b = ind.contact
        mm = 1e3
        xd, wd = ind.displacement.x, ind.displacement.w
        apex = spec.get("apex", 0.0)
        if spec["shape"] == "parabolic":
            f = lambda x: -(x - apex) ** 2 / (2 * spec["radius"])
            title = f"parabola, R = {spec['radius'] * mm:g} mm"
        else:
            s1, s2 = spec["slope_leading"], spec["slope_trailing"]
            f = lambda x: np.where(x < apex, s1 * (x - apex), -s2 * (x - apex))
            title = f"wedge, slopes {s1:g} / {s2:g}"
        # The displacement w is the surface's downward displacement relative to the leading edge a,
        # equal to the indentor's f - f(a) in contact: heights are -w and -(f - f(a)).
        um = 1e6
        surface = -wd * um
        face = -(f(xd) - f(a)) * um
        span = max(face.max(), surface.max()) - min(face.min(), surface.min())
        top_y = max(face.max(), surface.max()) + 0.45 * span
        bottom_y = surface.min() - 0.3 * span
        top.fill_between(xd * mm, surface, bottom_y, color="#c9dff2", lw=0)
        top.plot(xd * mm, surface, color="#1f5f99", lw=1.5)
        top.fill_between(xd * mm, face, top_y, color="0.78", lw=0)
        top.plot(xd * mm, face, color="0.35", lw=1.2)
        top.set_ylim(bottom_y, top_y)
        top.text(0.98, 0.06, "half-space, E(t) = E1 t^-alpha", transform=top.transAxes, ha="right", fontsize=8.5)
        top.text(0.98, 0.88, "rigid indentor", transform=top.transAxes, ha="right", fontsize=8.5)
        for x, name in ((a, "a"), (b, "b")):
            top.axvline(x * mm, color="k", lw=0.6, ls=":")
            bot.axvline(x * mm, color="k", lw=0.6, ls=":")
            bot.annotate(name, (x * mm, 1.0), xycoords=("data", "axes fraction"), textcoords="offset points",
                         xytext=(3, -12))
        top.annotate("", xy=(0.08, 0.88), xytext=(0.3, 0.88), xycoords="axes fraction",
                     arrowprops=dict(arrowstyle="->", lw=1.5))
        top.text(0.19, 0.92, "U", transform=top.transAxes, ha="center", va="bottom")
        top.set_title(title, fontsize=10)
        top.set_ylabel("height [um]")
        xp, pp = ind.pressure.x, ind.pressure.p
        lead, trail = ind.edges
        if lead.exponent > 0:  # a smooth edge: p -> 0 there
            xp, pp = np.concatenate(([a], xp)), np.concatenate(([0.0], pp))
        if trail.exponent > 0:
            xp, pp = np.concatenate((xp, [b])), np.concatenate((pp, [0.0]))
        bot.plot(xp * mm, pp * 1e-3, color="#b03a2e", lw=1.5)
        cap = np.quantile(pp, 0.97) * 1.3
        bot.set_ylim(0, cap * 1e-3)
        bot.set_xlabel("x [mm]")
        bot.set_ylabel("pressure [kPa]")
        text = (f"p ~ d^{lead.exponent:.3g} at a, d^{trail.exponent:.3g} at b" +
                ("\n|x - apex|^-alpha at the apex" if spec["shape"] == "wedge" else "") +
                f"\nC_f = {ind.hysteretic_friction:.3g}")
        right = spec["shape"] == "parabolic"  # the free side of the panel
        bot.text(0.98 if right else 0.02, 0.80, text, transform=bot.transAxes, va="top",
                 ha="right" if right else "left", fontsize=8.5)
    fig.suptitle(f"Rigid indentors sliding over a power-law viscoelastic half-space "
                 f"(alpha = {m['alpha']:g}, beta = {r.beta:.3g}): contact, pressure, friction", fontsize=10.5)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print("wrote", out)


if __name__ == "__main__":
    main(*sys.argv[1:])
