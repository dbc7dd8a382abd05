"""The worked study of docs/studies.md: run it and plot the smallest Jacobian over radius and crown.

Run: python benchmarks/tread_study.py   (writes docs/img/tread-shaping.png)
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import sectiondeform as sd

ROOT = Path(__file__).resolve().parents[1]


def main() -> None:
    rows = sd.sweep(ROOT / "docs" / "studies" / "tread-shaping.json", workers=2).to_pylist()
    fig, axes = plt.subplots(1, 2, figsize=(10, 4), sharey=True, constrained_layout=True)
    for ax, ratio in zip(axes, (0.9, 1.0)):
        sel = [r for r in rows if r["area_ratio"] == ratio]
        radii, crowns = sorted({r["bend_radius"] for r in sel}), sorted({r["crown"] for r in sel})
        grid = np.full((len(crowns), len(radii)), np.nan)
        for r in sel:
            if r["ok"]:
                grid[crowns.index(r["crown"]), radii.index(r["bend_radius"])] = r["jacobian_min"]
        im = ax.pcolormesh(np.abs(radii), crowns, grid, shading="nearest", cmap="viridis")
        ax.set_title(f"area ratio {ratio}")
        ax.set_xlabel("support radius (mm, convex drum)")
        fig.colorbar(im, ax=ax)
    axes[0].set_ylabel("crown sagitta (mm)")
    fig.suptitle("grooved tread: smallest final Jacobian (mm²) over support radius and crown")
    out = ROOT / "docs" / "img" / "tread-shaping.png"
    fig.savefig(out, dpi=110)
    ok = sum(r["ok"] for r in rows)
    print(f"{len(rows)} rows, {ok} ok, {len(rows) - ok} refused; wrote {out}")


if __name__ == "__main__":
    main()
