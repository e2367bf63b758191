"""Rewrites the two generated tables in README.md from the tools that define them:
`finger_model --parameters` (the actuator keys) and `finger_node --parameters` (the node's own).
The tests Cli.ReadmeParameterTableIsTheGeneratedOne and Cli.ReadmeNodeParameterTableIsTheGeneratedOne fail
until this has been run after a parameter changes.   usage: python3 scripts/update_readme_tables.py
"""
import pathlib
import subprocess

ROOT = pathlib.Path(__file__).resolve().parent.parent
BIN = ROOT / "devel/lib/pneumatic_finger"
readme = (ROOT / "README.md").read_text()
lines = readme.split("\n")
for tool, header in (("finger_model", "| key | symbol |"), ("finger_node", "| parameter | type |")):
    table = subprocess.run([str(BIN / tool), "--parameters"], check=True, capture_output=True, text=True).stdout.rstrip()
    start = next(i for i, l in enumerate(lines) if l.startswith(header))
    end = start
    while end < len(lines) and lines[end].startswith("|"):
        end += 1
    lines[start:end] = table.split("\n")
(ROOT / "README.md").write_text("\n".join(lines))
print("README.md tables updated")
