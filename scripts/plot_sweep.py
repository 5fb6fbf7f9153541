#!/usr/bin/env python3
"""Plots a speed sweep of `rhabel sweep` (CSV): hysteretic friction C_f of indentor 0 against sliding
speed (log axis), and below it the fitted power-law exponents (alpha from the slope of |E*|, and
from tan delta) and the contact frequency omega0 = U/L when the material is a master curve.
Rows whose status is not ok are marked in red (their status is printed).

Usage: /usr/bin/python3 scripts/plot_sweep.py SWEEP.csv OUT.png [--column speed]
(python3 + matplotlib; e.g. after `rhabel sweep examples/friction_speed_sweep.json --out F.csv`.)
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def number(text):
    return float(text) if text not in ("", None) else float("nan")


def main():
    args = sys.argv[1:]
    column = "speed"
    if "--column" in args:
        i = args.index("--column")
        column = args[i + 1]
        del args[i:i + 2]
    if len(args) != 2:
        sys.exit(__doc__)
    rows = list(csv.DictReader(open(args[0], newline="")))
    if not rows or column not in rows[0]:
        sys.exit(f"plot_sweep: {args[0]} has no column {column!r}")
    rows.sort(key=lambda r: number(r[column]))
    x = [number(r[column]) for r in rows]
    cf = [number(r.get("ind0_C_f")) for r in rows]
    bad = [(xi, ci, r["status"]) for xi, ci, r in zip(x, cf, rows) if r["status"] != "ok"]
    master = any(r.get("omega0") for r in rows)

    fig, axes = plt.subplots(2 if master else 1, 1, figsize=(7, 7 if master else 4.2), sharex=True, squeeze=False)
    ax = axes[0][0]
    ax.semilogx(x, cf, "o-", ms=3, color="tab:blue", label="hysteretic friction $C_f$")
    if bad:
        ax.semilogx([b[0] for b in bad], [b[1] for b in bad], "o", color="red", ms=6, mfc="none",
                    label="status not ok: " + ", ".join(sorted({b[2] for b in bad})))
    ax.set_ylabel("$C_f$")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(loc="best", fontsize=8)
    ax.set_title("Friction against sliding speed" if column == "speed" else f"Friction against {column}")
    if master:
        ax2 = axes[1][0]
        ax2.semilogx(x, [number(r["alpha"]) for r in rows], "-", label=r"$\alpha$ (slope of $|E^*|$)")
        ax2.semilogx(x, [number(r["alpha_tan_delta"]) for r in rows], "--", label=r"$\alpha = (2/\pi)\,\arctan\tan\delta$")
        ax2.set_ylabel(r"$\alpha$ at $\omega_0 = U/L$")
        ax2.grid(True, which="both", alpha=0.3)
        ax2.legend(loc="upper left", fontsize=8)
        ax3 = ax2.twinx()
        ax3.loglog(x, [number(r["omega0"]) for r in rows], ":", color="gray")
        ax3.set_ylabel(r"$\omega_0$ [rad/s] (dotted)")
        axes[1][0].set_xlabel("sliding speed U [m/s]" if column == "speed" else column)
    else:
        ax.set_xlabel("sliding speed U [m/s]" if column == "speed" else column)
    fig.tight_layout()
    fig.savefig(args[1], dpi=110)
    print(f"plot_sweep: wrote {args[1]} ({len(rows)} rows, {len(bad)} not ok)")


if __name__ == "__main__":
    main()
