#!/usr/bin/python3
"""Roofline chart of the element kernels and the nodal update (docs/performance.md).

    scripts/performance_roofline.py [DATA.json] [OUT.png]

DATA.json (default docs/figures/performance_roofline.json) holds the measured
numbers: the machine's ceilings (bench/machine/machine_peak_bench), and per kernel
the flops per element-cycle (scripts/performance_flop_count.py), the bytes per
element-cycle (counted in docs/performance.md) and the achieved rates
(bench/element/element_bench). Each kernel is drawn twice: filled at its DRAM
intensity with the rate of the 1e6-element box, hollow at its load/store-traffic
intensity with the rate of the in-cache 1.06e4-element box.
"""
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def main():
    data_path = sys.argv[1] if len(sys.argv) > 1 else "docs/figures/performance_roofline.json"
    out_path = sys.argv[2] if len(sys.argv) > 2 else "docs/figures/performance_roofline.png"
    with open(data_path) as f:
        data = json.load(f)
    machine = data["machine"]
    intensity = np.logspace(-1.3, 1.6, 200)  # flop / byte

    fig, ax = plt.subplots(figsize=(11.5, 5.0), dpi=110)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlim(intensity[0], intensity[-1])
    roof = next(c["value"] for c in machine["compute_gflops"] if c.get("roof"))  # the ceiling of the build
    ax.set_ylim(0.3, max(c["value"] for c in machine["compute_gflops"]) * 2.0)
    for ceiling in machine["compute_gflops"]:
        ax.axhline(ceiling["value"], color=ceiling.get("color", "0.3"), lw=1.2, ls=ceiling.get("style", "-"))
        ax.text(intensity[-1] * 0.95, ceiling["value"] * 1.04, f"{ceiling['label']}: {ceiling['value']:.1f}",
                ha="right", va="bottom", fontsize=8, color=ceiling.get("color", "0.3"))
    fig.canvas.draw()
    for band in machine["bandwidth_gbs"]:
        ax.plot(intensity, np.minimum(band["value"] * intensity, roof), color=band.get("color", "0.5"), lw=1.2,
                ls=band.get("style", "--"))
        # the label along the line, at the height given in the data
        y = band.get("label_at_gflops", 1.0)
        x = y / band["value"]
        p0, p1 = ax.transData.transform([(x, y), (2 * x, 2 * y)])
        angle = np.degrees(np.arctan2(p1[1] - p0[1], p1[0] - p0[0]))
        ax.text(x, y * 1.12, f"{band['label']}: {band['value']:.0f} GB/s", rotation=angle, rotation_mode="anchor",
                fontsize=8, color=band.get("color", "0.5"))

    for kernel in data["kernels"]:
        flops = kernel["flops_per_element"]
        color = kernel["color"]
        dram_ai = flops / kernel["dram_bytes_per_element"]
        dram_gflops = flops * kernel["rate_large_per_s"] * 1e-9
        traffic_ai = flops / kernel["traffic_bytes_per_element"]
        traffic_gflops = flops * kernel["rate_small_per_s"] * 1e-9
        ax.plot([dram_ai], [dram_gflops], marker=kernel["marker"], color=color, ms=8, ls="none",
                label=f"{kernel['label']} ({kernel['large_label']})")
        ax.plot([traffic_ai], [traffic_gflops], marker=kernel["marker"], mfc="none", mec=color, ms=8, ls="none")
        ax.plot([traffic_ai, dram_ai], [traffic_gflops, dram_gflops], color=color, lw=0.6, ls=":")

    ax.set_xlabel("arithmetic intensity (flop / byte)")
    ax.set_ylabel("GFLOP/s, one core")
    ax.set_title(data.get("title", "roofline"), fontsize=10)
    ax.grid(True, which="both", lw=0.3, color="0.85")
    # beside the chart: inside it the legend hid the kernels near the ridge
    ax.legend(fontsize=7.5, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0,
              title="filled: DRAM bytes, large mesh;\nhollow: load/store bytes, in cache", title_fontsize=7)
    fig.tight_layout()
    fig.savefig(out_path)
    print(f"wrote {out_path}")


if __name__ == "__main__":
    main()
