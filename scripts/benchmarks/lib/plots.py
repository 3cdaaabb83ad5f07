"""What the benchmarks' plots share: matplotlib without a display, saving a
figure, and grouped bars per sphere set on a log axis."""
from .common import isnum


def pyplot():
    """matplotlib.pyplot on the Agg backend (no display)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def save(fig, path, **kw):
    """Lays the figure out, writes it to `path` (returned) and frees it."""
    import matplotlib.pyplot as plt
    fig.tight_layout()
    fig.savefig(path, **kw)
    plt.close(fig)
    return path


def set_bars(ax, sets, keys, span, ylabel, **legend):
    """Per set (a dict with 'set', 'spheres' and the keys) one bar per
    (key, label) of `keys` that some set has, the group `span` wide; log y."""
    keys = [k for k in keys if any(isnum(s.get(k[0])) for s in sets)]
    wbar = span / max(len(keys), 1)
    for i, (k, label) in enumerate(keys):
        ys = [s.get(k) if isnum(s.get(k)) else float("nan") for s in sets]
        ax.bar([j + i * wbar for j in range(len(sets))], ys, wbar, label=label)
    ax.set_xticks([j + span / 2 - wbar / 2 for j in range(len(sets))])
    ax.set_xticklabels([f"{s['set'].upper()}\n{s['spheres']:,}" for s in sets], fontsize=8)
    ax.set_yscale("log")
    ax.set_ylabel(ylabel)
    ax.grid(True, axis="y", which="both", alpha=0.3)
    ax.legend(**legend)
