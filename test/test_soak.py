"""The cell's 50-cycle soak (scripts/soak_cell.py; the long run is docs/SOAK.md): every cycle completes and carries
the object, and no process's resident memory grows after warm-up by more than 2 MB (the 1000-cycle run's bound is
1 MB; fifty cycles leave the allocators less time to settle).

Run by `make run_tests` (CMakeLists.txt), with the package's devel space sourced.
"""
import csv
import pathlib
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent


def test_fifty_cycles_complete_carry_and_keep_memory_flat(tmp_path):
    table = tmp_path / "soak.csv"
    done = subprocess.run([sys.executable, str(ROOT / "scripts" / "soak_cell.py"), "50", "--csv", str(table),
                           "--max-rss-growth-mb", "2"], capture_output=True, text=True, timeout=900)
    assert done.returncode == 0, done.stdout + done.stderr
    rows = list(csv.DictReader(open(table)))
    assert [int(r["cycle"]) for r in rows] == list(range(1, 51))
    assert all(r["outcome"] == "carried" for r in rows), [r["outcome"] for r in rows]
    # The checks the script made are its own; the memory column is there for every process it found.
    assert any(k.startswith("rss_kb nodelet manager") and rows[-1][k] for k in rows[-1]), rows[-1]
