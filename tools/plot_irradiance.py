#!/usr/bin/python3
"""Plots error against precomputation time for each irradiance mode from the CSV written by
`insitu irradiance-report ... --csv docs/irradiance.csv` (needs python3-matplotlib).

    /usr/bin/python3 tools/plot_irradiance.py docs/irradiance.csv docs/images/irradiance-error-vs-time.png
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

rows = list(csv.DictReader(open(sys.argv[1])))
colours = {"gaussian": "tab:red", "sh9": "tab:blue", "exact": "tab:green"}
fig, axes = plt.subplots(1, 2, figsize=(10, 4.2))
for ax, column, title in ((axes[0], "mean_rel_error", "mean relative error"),
                          (axes[1], "max_rel_error", "maximum relative error")):
    for mode, colour in colours.items():
        pts = [r for r in rows if r["mode"] == mode]
        ax.scatter([float(r["precompute_ms"]) for r in pts], [float(r[column]) for r in pts],
                   c=colour, label=mode, s=28)
        for r in pts:
            ax.annotate(r["environment"], (float(r["precompute_ms"]), float(r[column])), fontsize=6,
                        xytext=(3, 2), textcoords="offset points")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("precomputation time (ms, 2 cores)")
    ax.set_ylabel(title)
    ax.grid(True, which="both", alpha=0.3)
axes[0].legend()
fig.suptitle("Irradiance modes against the exact integral (one point per environment)")
fig.tight_layout()
fig.savefig(sys.argv[2], dpi=110)
