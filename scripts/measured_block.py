"""Replaces a measured block of a Markdown file with standard input. A block is delimited by
    <!-- measured by COMMAND: begin -->  and  <!-- measured: end -->
so that the page says which command measured what it shows, and a rerun of that command refreshes it. Measured
blocks (timings, CPU shares) differ from run to run, so no test compares them; the blocks a command prints the same
way every time are "generated" blocks, which scripts/update_docs.py rewrites and checks.

usage: COMMAND | python3 scripts/measured_block.py FILE 'COMMAND'
"""
import pathlib
import sys

path, command = pathlib.Path(sys.argv[1]), sys.argv[2]
begin, end = f"<!-- measured by {command}: begin -->", "<!-- measured: end -->"
text = path.read_text()
if begin not in text:
    sys.exit(f"measured_block: {path} has no block '{begin}'")
head, rest = text.split(begin, 1)
_, tail = rest.split(end, 1)
body = sys.stdin.read().rstrip("\n")
path.write_text(f"{head}{begin}\n```\n{body}\n```\n{end}{tail}")
print(f"measured_block: {path}: block of '{command}' updated")
