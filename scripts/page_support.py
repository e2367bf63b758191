"""What the scripts that write a docs/ page with its plot share: the --plot argument and saving the figure."""
import argparse


def plot_arguments(doc, default_png):
    """The command line of a page's script: --plot PATH (default: the page's own PNG)."""
    parser = argparse.ArgumentParser(description=doc.splitlines()[0])
    parser.add_argument("--plot", default=str(default_png), help="where to write the figure (PNG)")
    return parser.parse_args()


def save(fig, path):
    """The figure, laid out, at the pages' resolution."""
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def finish_axes(ax, title, legend_size=8, legend_columns=1):
    """One panel in the pages' style: a small title, a legend and a light grid."""
    ax.set_title(title, fontsize=10)
    ax.legend(fontsize=legend_size, ncol=legend_columns)
    ax.grid(alpha=0.3)
