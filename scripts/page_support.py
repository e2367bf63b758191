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
