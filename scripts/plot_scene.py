#!/usr/bin/python3
"""Plot the result of `rhabel solve --grid N` as a PNG: contact pressure (top) and surface
displacement (bottom) of every indentor, contact edges marked.

    /usr/bin/python3 scripts/plot_scene.py RESULT.json OUT.png [--units si|raw]

RESULT.json is the JSON printed by `rhabel solve SCENE --grid N` (it must contain the sampled
fields "pressure" and "displacement" of each indentor). With --units si (the default) the scene
is taken to be in SI units (m, Pa, N/m) and the axes are labelled in mm, MPa and micrometres;
with --units raw the numbers are plotted as they are, in the scene's own consistent units.

Singular edges (pressure ~ distance^exponent with exponent < 0) are marked with a red triangle
and the pressure axis is clipped above the regular part of the curves, so that an integrable
singularity does not flatten the rest of the plot; the clipping is written on the figure.

Uses matplotlib (Debian: python3-matplotlib); run it with /usr/bin/python3.
"""
import argparse
import json
import sys
import textwrap


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("result", help="JSON from `rhabel solve SCENE --grid N` ('-' for stdin)")
    parser.add_argument("png", help="output PNG file")
    parser.add_argument("--units", choices=["si", "raw"], default="si")
    parser.add_argument("--title", default=None, help="figure title (default: the scene description)")
    args = parser.parse_args(argv)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    with (sys.stdin if args.result == "-" else open(args.result, encoding="utf-8")) as f:
        result = json.load(f)
    indentors = result["indentors"]
    if not all("pressure" in ind and "displacement" in ind for ind in indentors):
        sys.exit("plot_scene.py: the result has no sampled fields: run `rhabel solve SCENE --grid N`")

    if args.units == "si":
        sx, ux = 1e3, "mm"
        sp, up = 1e-6, "MPa"
        sw, uw = 1e6, "\u00b5m"
    else:
        sx, ux = 1.0, "scene units"
        sp, up = 1.0, "scene units"
        sw, uw = 1.0, "scene units"

    # One column per indentor (contacts are usually much narrower than their spacing).
    n = len(indentors)
    fig, axes = plt.subplots(2, n, figsize=(max(9.0, 4.8 * n + 1.0), 7.5), sharex="col", squeeze=False,
                             gridspec_kw={"height_ratios": [1.15, 1.0]})
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    any_singular = False
    for i, ind in enumerate(indentors):
        ax_p, ax_w = axes[0][i], axes[1][i]
        clip = 0.0          # top of the pressure axis
        clipped = False
        c = colours[i % len(colours)]
        label = ind.get("name") or f"{ind.get('shape', 'indentor')} #{i}"
        a, b = ind["contact"]
        length = max(b - a, 0.0)
        edges = ind.get("edges", [])
        singular_at = [e["at"] for e in edges if e.get("singular")]
        if ind.get("peak_pressure_singular"):  # e.g. the apex of a wedge (weak singularity)
            singular_at.append(ind["peak_pressure_at"])

        # Pressure: add p = 0 at regular edges (exponent > 0) so that the curve closes there.
        xs = list(ind["pressure"]["x"])
        ps = list(ind["pressure"]["p"])
        for e in edges:
            if not e.get("singular") and e.get("exponent", 0) > 0:
                if e["side"] == "leading":
                    xs.insert(0, e["at"]); ps.insert(0, 0.0)
                else:
                    xs.append(e["at"]); ps.append(0.0)
        ax_p.plot([x * sx for x in xs], [p * sp for p in ps], color=c, lw=1.8)
        ax_p.set_title(f"{label}\ncontact [{a * sx:.4g}, {b * sx:.4g}] {ux}", fontsize=9)

        # Regular part of the curve: points farther than 3% of L from any singular edge.
        regular = [p for x, p in zip(xs, ps)
                   if all(abs(x - s) > 0.03 * length for s in singular_at)] or ps
        top = max(regular) * sp
        clip = max(clip, top)
        if singular_at and max(ps) * sp > 1.6 * top:
            clipped = True
        if ind.get("peak_pressure") is not None and not ind.get("peak_pressure_singular"):
            ax_p.plot(ind["peak_pressure_at"] * sx, ind["peak_pressure"] * sp, "o", color=c, ms=5)

        # Edges on both panels: dashed lines, singular ones with a red triangle on the p-axis.
        for e in edges:
            for ax in (ax_p, ax_w):
                ax.axvline(e["at"] * sx, color=c, ls="--", lw=0.8, alpha=0.7)
            if e.get("singular"):
                any_singular = True
                ax_p.plot(e["at"] * sx, 0, marker="^", color="red", ms=9, clip_on=False, zorder=5)

        ax_w.plot([x * sx for x in ind["displacement"]["x"]],
                  [w * sw for w in ind["displacement"]["w"]], color=c, lw=1.8)
        ax_w.axvspan(a * sx, b * sx, color=c, alpha=0.08)
        if ind.get("peak_pressure_singular"):
            any_singular = True
            ax_p.plot(ind["peak_pressure_at"] * sx, 0, marker="^", color="red", ms=9, clip_on=False, zorder=5)
        ax_p.set_ylim(0, 1.25 * clip if clip > 0 else 1)
        if clipped:
            ax_p.text(0.99, 0.97, "axis clipped: p \u2192 \u221e at the red triangle", transform=ax_p.transAxes,
                      ha="right", va="top", fontsize=8, color="red")
        ax_p.grid(alpha=0.3)
        ax_w.grid(alpha=0.3)
        ax_w.set_xlabel(f"x [{ux}]")

    axes[0][0].set_ylabel(f"contact pressure p [{up}]")
    axes[1][0].set_ylabel(f"surface displacement w [{uw}]")
    note = ("indentors slide towards \u2212x; dashed: contact edges (left = leading a, right = trailing b); "
            "dots: peak pressure; shaded: contact; w is relative to its value at the leading edge")
    if any_singular:
        note += "\nred triangles: singular points (integrable pressure singularity: an edge with exponent < 0, or a wedge apex)"
    fig.text(0.01, 0.005, "\n".join(textwrap.fill(line, 150) for line in note.split("\n")),
             fontsize=8, va="bottom")

    material = result.get("scene", {}).get("material", {})
    title = args.title
    if title is None:
        title = (f"alpha = {material.get('alpha', '?')}, E1 = {material.get('E1', '?'):.3g}, "
                 f"nu = {material.get('nu', '?')}, k = {material.get('coulomb', '?')}, "
                 f"U = {result.get('scene', {}).get('speed', '?')}; "
                 f"beta = {result['beta']:.3g}, regime: {result['regime']}")
    fig.suptitle(textwrap.fill(title, 110), fontsize=10)
    fig.tight_layout(rect=(0, 0.05, 1, 1))
    fig.savefig(args.png, dpi=130)
    return 0


if __name__ == "__main__":
    sys.exit(main())
