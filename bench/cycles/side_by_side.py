#!/usr/bin/python3
"""The side-by-side figures of bench/cycles/run.sh (issue 16), from its output folder:

    /usr/bin/python3 bench/cycles/side_by_side.py OUT_DIR MASK.png [OBJECTS_MASK.png]

For each renderer (cycles_*.exr with cycles_times.json, insitu_*.exr with insitu_times.csv):
  noise(s)   relative RMSE over the mask (objects + changed pixels), RGB, against the renderer's own
             reference R of another seed: sqrt(Σ (a − r)²) / sqrt(Σ r²). R is noisy too: with
             variance ∝ 1/spp, E[noise²] = σ²(s) (1 + s/R_spp), so σ(s) = noise / sqrt(1 + s/R_spp).
  σ·√s      at each rung: constant for independent samples (σ = σ₁/√s); falling with s for
             quasi-Monte Carlo points (both renderers' samplers), whose error falls faster.
  seconds    t(s) = t₀ + k·s fitted by least squares (t₀: what does not scale with spp).
  to 2 %     from the rung whose σ is nearest 2 %, along the 1/√spp line through it:
             s₂ = s (σ(s) / 0.02)², and t(s₂). (A single 1/√spp line fitted through the whole
             ladder would misjudge a renderer whose σ·√s falls.)
  by region  with OBJECTS_MASK (the validation's mask_objects.png), σ at each rung over the objects
             and over the rest of MASK (shadows, bounce light) apart.
Writes OUT_DIR/side_by_side.md (the tables) and, with python3-matplotlib, OUT_DIR/side_by_side.png
(noise against seconds, log-log).
"""
import csv
import json
import math
import os
import platform
import sys

import numpy as np
import OpenImageIO as oiio

TARGET = 0.02


def read(path):
    buf = oiio.ImageBuf(path)
    if buf.has_error:
        sys.exit(f"side_by_side: {path}: {buf.geterror()}")
    return buf.get_pixels(oiio.FLOAT)[:, :, :3].astype(np.float64)


def noise(image, ref, mask):
    d, r = (image - ref)[mask], ref[mask]
    return math.sqrt(float(np.sum(d * d)) / float(np.sum(r * r)))


def renderer(out, name, times, mask):
    """Rows (spp, seconds, noise, σ) of the ladder and the fitted figures."""
    ref = read(os.path.join(out, f"{name}_reference.exr"))
    ref_spp = times["reference"][0]
    rows = []
    for key, (spp, seconds) in sorted(times.items(), key=lambda kv: kv[1][0]):
        if key == "reference":
            continue
        n = noise(read(os.path.join(out, f"{name}_{key}.exr")), ref, mask)
        rows.append((spp, seconds, n, n / math.sqrt(1 + spp / ref_spp)))
    k, t0 = np.polyfit([r[0] for r in rows], [r[1] for r in rows], 1)
    near = min(rows, key=lambda r: abs(math.log(r[3] / TARGET)))
    spp2 = near[0] * (near[3] / TARGET) ** 2
    return {"rows": rows, "t0": t0, "k": k, "spp2": spp2, "t2": t0 + k * spp2, "from_spp": near[0],
            "ref_spp": ref_spp}


def by_region(out, times, objects, rest):
    """Lines of σ at each rung over the objects and over the rest of the mask, for each renderer."""
    lines = ["", "| renderer | spp | σ, objects | σ, shadows and other changed pixels |", "|---|---|---|---|"]
    for name, label in (("cycles", "Cycles 3.4"), ("insitu", "insitu path")):
        ref = read(os.path.join(out, f"{name}_reference.exr"))
        ref_spp = times[name]["reference"][0]
        for key, (spp, _) in sorted(times[name].items(), key=lambda kv: kv[1][0]):
            if key == "reference":
                continue
            image = read(os.path.join(out, f"{name}_{key}.exr"))
            s_obj, s_rest = (noise(image, ref, m) / math.sqrt(1 + spp / ref_spp) for m in (objects, rest))
            lines.append(f"| {label} | {spp} | {100 * s_obj:.2f} % | {100 * s_rest:.2f} % |")
    return lines


def main():
    out, mask_path = sys.argv[1], sys.argv[2]
    mask = read(mask_path)[:, :, 0] > 0.5
    cj = json.load(open(os.path.join(out, "cycles_times.json")))
    cycles_times = {k: (v["spp"], v["seconds"]) for k, v in cj["renders"].items()}
    insitu_times = {r[0]: (int(r[1]), float(r[2])) for r in csv.reader(open(os.path.join(out, "insitu_times.csv")))}
    fits = {"Cycles 3.4": renderer(out, "cycles", cycles_times, mask),
            "insitu path": renderer(out, "insitu", insitu_times, mask)}
    cpu = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), "?")
    lines = [f"Machine: {cpu}, {os.cpu_count()} threads used by both ({platform.node()}); "
             f"mask: {int(mask.sum())} pixels (objects + changed).", "",
             "| renderer | spp | seconds | noise vs own reference | σ (reference's noise removed) | σ·√spp |",
             "|---|---|---|---|---|---|"]
    for name, f in fits.items():
        for spp, seconds, n, s in f["rows"]:
            lines.append(f"| {name} | {spp} | {seconds:.1f} | {100 * n:.2f} % | {100 * s:.2f} % | "
                         f"{100 * s * math.sqrt(spp):.1f} % |")
    lines += ["", "| renderer | seconds = t₀ + k·spp | spp to 2 % (from the rung at) | seconds to 2 % |",
              "|---|---|---|---|"]
    for name, f in fits.items():
        lines.append(f"| {name} | {f['t0']:.2f} + {1000 * f['k']:.2f} ms·spp | {f['spp2']:.0f} ({f['from_spp']}) | "
                     f"{f['t2']:.1f} |")
    c, i = fits["Cycles 3.4"]["t2"], fits["insitu path"]["t2"]
    lines += ["", f"insitu / Cycles, time to 2 %: {i / c:.3f} (goal ≤ 0.2)."]
    if len(sys.argv) > 3:
        objects = read(sys.argv[3])[:, :, 0] > 0.5
        lines += by_region(out, {"cycles": cycles_times, "insitu": insitu_times}, objects & mask, mask & ~objects)
    text = "\n".join(lines) + "\n"
    open(os.path.join(out, "side_by_side.md"), "w").write(text)
    print(text, end="")
    plot(out, fits)


def plot(out, fits):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("side_by_side: python3-matplotlib is not installed: no plot")
        return
    fig, ax = plt.subplots(figsize=(6, 4.2))
    for (name, f), colour in zip(fits.items(), ("tab:orange", "tab:blue")):
        ax.plot([r[1] for r in f["rows"]], [r[3] for r in f["rows"]], "o-", color=colour, label=name)
        for spp, seconds, _, s in f["rows"]:
            ax.annotate(str(spp), (seconds, s), fontsize=7, xytext=(3, 3), textcoords="offset points")
        ax.plot([f["t2"]], [TARGET], "x", color=colour, markersize=9)
    ax.axhline(TARGET, color="grey", lw=0.8, ls="--")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("seconds (wall clock, all cores)")
    ax.set_ylabel("relative RMSE, objects + changed pixels")
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(out, "side_by_side.png"), dpi=110)
    print("side_by_side: wrote", os.path.join(out, "side_by_side.png"))


main()
