"""Figures of the local search study (matplotlib, Agg backend, PNG at 100 dpi)."""

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.colors import ListedColormap  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402
import numpy as np  # noqa: E402

# Colours by kind of end point; the closest point is always green.
_PALETTE = {
    "closest point": ["#2ca02c", "#98df8a", "#b5e6a9"],
    "minimum": ["#1f77b4", "#17becf", "#9467bd", "#aec7e8", "#c5b0d5"],
    "saddle": ["#d62728"],
    "maximum": ["#8c564b"],
    "converged elsewhere": ["#bcbd22"],
    "not converged": ["#7f7f7f"],
}


def _colours(names):
    used = {k: 0 for k in _PALETTE}
    out = []
    for n in names:
        key = next((k for k in ("closest point", "converged elsewhere", "not converged", "saddle", "maximum",
                                "minimum") if n.startswith(k)), "minimum")
        pal = _PALETTE[key]
        out.append(pal[min(used[key], len(pal) - 1)])
        used[key] += 1
    return out


def basins(b, methods, path, case_name):
    """One subplot per method: the end point of each starting point, coloured by label."""
    rows, labels, names, grid, s = b["rows"], b["labels"], b["label_names"], b["grid"], b["s"]
    colours = _colours(names)
    cmap = ListedColormap(colours)
    ncol = 3
    nrow = int(np.ceil(len(methods) / ncol))
    fig, axes = plt.subplots(nrow, ncol, figsize=(3.0 * ncol, 3.2 * nrow + 0.9), squeeze=False)
    h = s[1] - s[0] if len(s) > 1 else 1.0
    extent = [s[0] - h / 2, s[-1] + h / 2, s[0] - h / 2, s[-1] + h / 2]
    stars = np.array(b["closest"]).reshape(-1, 2)
    closest_labels = [i for i, n in enumerate(names) if n.startswith("closest point")]
    for ax, m in zip(axes.ravel(), methods):
        sel = rows["method"] == m
        img = np.full((grid, grid), -1)
        # case id k is starting point k of the grid (meshgrid 'ij': k = i * grid + j)
        ids = rows["id"][sel]
        img[ids // grid, ids % grid] = labels[sel]
        ax.imshow(img.T, origin="lower", extent=extent, cmap=cmap, vmin=-0.5, vmax=len(names) - 0.5,
                  interpolation="nearest")
        ax.plot(stars[:, 0], stars[:, 1], marker="*", color="k", markersize=9, linestyle="none")
        ok = np.isin(labels[sel], closest_labels).mean()
        ax.set_title(f"{m}: {100 * ok:.0f} % to a closest point", fontsize=9)
        ax.set_xticks([-1, 0, 1])
        ax.set_yticks([-1, 0, 1])
        ax.tick_params(labelsize=7)
    for ax in axes.ravel()[len(methods):]:
        ax.axis("off")
    for ax in axes[-1]:
        ax.set_xlabel("start xi1", fontsize=8)
    for ax in axes[:, 0]:
        ax.set_ylabel("start xi2", fontsize=8)
    handles = [Patch(color=c, label=n) for c, n in zip(colours, names)]
    fig.legend(handles=handles, loc="lower center", ncol=2, fontsize=8, frameon=False, bbox_to_anchor=(0.5, 0.0))
    fig.suptitle(f"{case_name}: where each starting point ends (stars: the closest points)", fontsize=11)
    legend_rows = (len(names) + 1) // 2
    fig.subplots_adjust(left=0.07, right=0.98, top=0.93, bottom=0.06 + 0.022 * legend_rows, hspace=0.32, wspace=0.22)
    fig.savefig(path, dpi=100)
    plt.close(fig)


def speed_accuracy(sp, path, cases):
    """Mean time per projection against the share ending on the closest point."""
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    x = np.array([s["mean_ns"] for s in sp])
    y = np.array([100 * s["success"] for s in sp])
    ax.scatter(x, y, color="#1f77b4", zorder=3)
    order = np.argsort(x)
    for rank, i in enumerate(order):  # alternate label sides so neighbours do not overlap
        ax.annotate(sp[i]["method"], (x[i], y[i]), textcoords="offset points",
                    xytext=(4, 6 if rank % 2 == 0 else -12), fontsize=8)
    ax.set_xscale("log")
    ax.set_xlim(x.min() / 1.3, x.max() * 1.4)  # room for the labels
    ax.set_xlabel("mean time per projection [ns] (log scale)")
    ax.set_ylabel("runs ending on the true closest point [%]")
    ax.set_title(f"Speed against accuracy, {cases} random segments, guess lsp", fontsize=10)
    lo = max(0.0, np.floor(y.min()) - 2)
    ax.set_ylim(lo, 100.5)
    ticks = [t for t in (50, 100, 200, 500, 1000, 2000, 5000, 10000, 20000, 50000)
             if x.min() / 1.5 <= t <= x.max() * 1.5]
    ax.set_xticks(ticks)
    ax.set_xticklabels([str(t) for t in ticks])
    ax.minorticks_off()
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
