"""A long run of the pick-and-place cell, measured: memory, CPU, latency and grasps, cycle by cycle.

usage: python3 scripts/soak_cell.py CYCLES [--cycle-time S] [--object-mass KG] [--csv FILE] [--doc docs/SOAK.md]
                                   [--max-rss-growth-mb MB]
       (bash scripts/soak_cell.sh CYCLES runs it with the ROS environment; after scripts/build.sh)

Starts the cell headless (launch/pick_and_place_cell.launch, rviz:=false) at --cycle-time (default 2 s, the shortest
its schedule accepts; the cell waits for the gripper where the fill outlasts the grasp phase) with an --object-mass
part (default 3 g; the sequencer asks the grip that part and that lift need), for CYCLES cycles, and samples,
at every completed cycle: every process's resident memory (VmRSS) and CPU time (/proc), the grasp's outcome
(cell/events), the warnings and errors on /rosout, and the latency from the regulator's publish to finger A's
joint_states at a subscriber (their stamps are the pressure's). Writes one CSV row per cycle; with --doc, the page
(figures and verdicts, computed here) and its plots beside it. Exits 1, saying why, when a cycle did not complete,
a grasp missed, or a process's memory grew after warm-up (the first 10 % of the cycles, at least 5) by more than
--max-rss-growth-mb (default 1 MB).
"""
import argparse
import csv
import math
import os
import pathlib
import re
import signal
import socket
import subprocess
import sys
import threading
import time

from page_support import finish_axes

ROOT = pathlib.Path(__file__).resolve().parent.parent
PROCESSES = ("nodelet manager", "cell_sequencer", "gripper_action_server", "robot_state_publisher", "rosmaster",
             "rosout")
CLK_TCK = os.sysconf("SC_CLK_TCK")


def free_port():
    s = socket.socket()
    s.bind(("localhost", 0))
    return s.getsockname()[1]


def find_processes():
    """name -> pid of the cell's processes (by their command lines)."""
    found = {}
    for pid in os.listdir("/proc"):
        if not pid.isdigit():
            continue
        try:
            cmd = open(f"/proc/{pid}/cmdline", "rb").read().replace(b"\0", b" ").decode(errors="replace")
        except OSError:
            continue
        for name in PROCESSES:
            if re.search(rf"/{re.escape(name)}( |$)", cmd) or (name == "nodelet manager" and "nodelet manager" in cmd):
                found.setdefault(name, int(pid))
    return found


def sample(pid):
    """(RSS in kB, CPU seconds) of a process, or None when it is gone."""
    try:
        rss = int(re.search(r"VmRSS:\s+(\d+)", open(f"/proc/{pid}/status").read()).group(1))
        fields = open(f"/proc/{pid}/stat").read().rsplit(")", 1)[1].split()
        return rss, (int(fields[11]) + int(fields[12])) / CLK_TCK
    except (OSError, AttributeError):
        return None


class Monitor:
    """The cell's topics: cycles, events, warnings, finger A's latency."""

    def __init__(self):
        import rospy
        from rosgraph_msgs.msg import Log
        from sensor_msgs.msg import JointState
        from std_msgs.msg import String, UInt32
        self.lock = threading.Lock()
        self.cycles, self.events, self.latencies_us, self.warnings, self.errors = 0, [], [], 0, 0
        self.warning_texts = []
        rospy.init_node("soak_monitor", anonymous=True, disable_signals=True)
        rospy.Subscriber("/cell/cycles", UInt32, self.on_cycles, queue_size=100)
        rospy.Subscriber("/cell/events", String, self.on_event, queue_size=100)
        rospy.Subscriber("/rosout_agg", Log, self.on_log, queue_size=1000)
        rospy.Subscriber("/joint_states", JointState, self.on_joints, queue_size=1000, tcp_nodelay=True)

    def on_cycles(self, msg):
        with self.lock:
            self.cycles = max(self.cycles, msg.data)

    def on_event(self, msg):
        with self.lock:
            self.events.append(msg.data)

    def on_log(self, msg):
        if msg.level >= msg.WARN and msg.name != "/soak_monitor" and "soak_monitor" not in msg.name:
            with self.lock:
                self.warnings += msg.level == msg.WARN
                self.errors += msg.level >= msg.ERROR
                if len(self.warning_texts) < 20:
                    self.warning_texts.append(f"{msg.name}: {msg.msg}")

    def on_joints(self, msg):
        now = time.time()
        if msg.name and msg.name[0].startswith("finger_a_"):
            with self.lock:
                self.latencies_us.append(1e6 * (now - msg.header.stamp.to_sec()))

    def take(self):
        with self.lock:
            out = (self.cycles, list(self.events), self.latencies_us, self.warnings, self.errors)
            self.events, self.latencies_us = [], []
            return out


def percentile(values, q):
    if not values:
        return math.nan
    v = sorted(values)
    return v[min(len(v) - 1, int(q * len(v)))]


def run(cycles, csv_path, cycle_time_s, object_mass_kg):
    port = free_port()
    env = dict(os.environ, ROS_MASTER_URI=f"http://localhost:{port}")
    os.environ["ROS_MASTER_URI"] = env["ROS_MASTER_URI"]
    log = open(ROOT / "build" / "soak_cell.log", "w")
    # The master first, then this monitor, then the cell: the cell starts its first cycle at once, and the monitor must
    # not miss it.
    master = subprocess.Popen(["roscore", "-p", str(port)], env=env, stdout=log, stderr=subprocess.STDOUT)
    for _ in range(200):
        if subprocess.run(["rostopic", "list"], env=env, capture_output=True).returncode == 0:
            break
        time.sleep(0.1)
    monitor = Monitor()
    launch = subprocess.Popen(["roslaunch", "pneumatic_finger", "pick_and_place_cell.launch", "rviz:=false",
                               f"cycle_time:={cycle_time_s}", f"object_mass:={object_mass_kg}",
                               f"loop_count:={cycles}"], env=env, stdout=log,
                              stderr=subprocess.STDOUT)
    processes, rows = {}, []
    outcome_of_cycle, done, pending, started = {}, 0, [], time.time()
    deadline = started + 60 + 4 * (cycle_time_s + 0.5) * cycles  # four times the cycle is a stall
    with open(csv_path, "w", newline="") as f:
        writer = None
        ended = None  # the launch stops itself after the last cycle: its last messages still count, for 2 s
        while done < cycles and time.time() < deadline and (ended is None or time.time() < ended + 2):
            time.sleep(0.05)
            if ended is None and launch.poll() is not None:
                ended = time.time()
            now_cycles, events, latencies, warnings, errors = monitor.take()
            for e in events:
                m = re.match(r"cycle (\d+): (grasped|grasp missed)", e)
                if m:
                    outcome_of_cycle[int(m.group(1))] = "carried" if m.group(2) == "grasped" else "missed"
            pending += latencies  # since the last completed cycle
            if len(processes) < len(PROCESSES):
                processes.update({k: v for k, v in find_processes().items() if k not in processes})
            if now_cycles <= done:
                continue
            samples = {name: sample(pid) for name, pid in processes.items()}
            for cycle in range(done + 1, now_cycles + 1):  # one row per cycle, even when two end between samples
                row = {"cycle": cycle, "time_s": round(time.time() - started, 3),
                       "outcome": outcome_of_cycle.get(cycle, "unknown"), "warnings": warnings, "errors": errors,
                       "latency_p50_us": round(percentile(pending, 0.5), 1),
                       "latency_p99_us": round(percentile(pending, 0.99), 1), "latency_samples": len(pending)}
                for name in PROCESSES:
                    s = samples.get(name)
                    row[f"rss_kb {name}"] = s[0] if s else ""
                    row[f"cpu_s {name}"] = round(s[1], 3) if s else ""
                if writer is None:
                    writer = csv.DictWriter(f, fieldnames=list(row.keys()))
                    writer.writeheader()
                writer.writerow(row)
                rows.append(row)
            f.flush()
            done, pending = now_cycles, []
    for p in (launch, master):
        p.send_signal(signal.SIGINT)
        try:
            p.wait(timeout=30)
        except subprocess.TimeoutExpired:
            p.kill()
    return rows, monitor.warning_texts, processes


def quarters(rss_kb):
    """The growth in each quarter of the run after warm-up, in words: whether a process's memory levels off (each
    quarter adds less) or keeps climbing (each adds about the same). Empty for a run too short to cut in four."""
    n = len(rss_kb)
    if n < 8:
        return ""
    cuts = [rss_kb[(n - 1) * k // 4] for k in range(5)]
    return " (by quarter: " + ", ".join(f"+{(b - a) / 1024:.2f}" for a, b in zip(cuts, cuts[1:])) + " MB)"


def verdicts(rows, cycles, max_growth_mb, processes):
    """The run's figures and what failed (empty: nothing)."""
    failed, lines = [], []
    if len(rows) < cycles:
        failed.append(f"{len(rows)} of {cycles} cycles completed")
    missed = [r["cycle"] for r in rows if r["outcome"] != "carried"]
    lines.append(f"cycles completed: {len(rows)} of {cycles}; grasps carried: {len(rows) - len(missed)}"
                 + (f"; not carried: cycles {missed[:10]}" if missed else ""))
    if missed:
        failed.append(f"cycles {missed[:10]} did not carry the object")
    warm = max(5, len(rows) // 10)
    for name in processes:
        rss = [r[f"rss_kb {name}"] for r in rows[warm:] if r.get(f"rss_kb {name}") != ""]
        cpu = [r[f"cpu_s {name}"] for r in rows if r.get(f"cpu_s {name}") != ""]
        if len(rss) < 2:
            continue
        growth_mb = (max(rss) - rss[0]) / 1024
        span = rows[-1]["time_s"] - rows[0]["time_s"]
        share = 100 * (cpu[-1] - cpu[0]) / span if span > 0 and len(cpu) > 1 else math.nan
        lines.append(f"{name}: RSS {rss[0] / 1024:.1f} MB after warm-up (cycle {warm + 1}), largest {max(rss) / 1024:.1f}"
                     f" MB: +{growth_mb:.2f} MB{quarters(rss)}; CPU {share:.1f} % of one core")
        if growth_mb > max_growth_mb:
            failed.append(f"{name}'s RSS grew by {growth_mb:.2f} MB after warm-up (bound {max_growth_mb} MB)")
    return lines, failed


def latency_blocks(rows, block=100):
    """Per block of cycles: (first cycle, median of the cycles' p50, largest p99)."""
    out = []
    for i in range(0, len(rows), block):
        part = [r for r in rows[i:i + block] if not math.isnan(float(r["latency_p99_us"]))]
        if part:
            out.append((rows[i]["cycle"], percentile([float(r["latency_p50_us"]) for r in part], 0.5),
                        max(float(r["latency_p99_us"]) for r in part)))
    return out


def plot(rows, processes, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(12, 4.2))
    cycles = [r["cycle"] for r in rows]
    for name in processes:
        rss = [r[f"rss_kb {name}"] / 1024 if r.get(f"rss_kb {name}") != "" else math.nan for r in rows]
        ax1.plot(cycles, rss, label=name)
    ax1.set_xlabel("cycle")
    ax1.set_ylabel("resident memory (MB)")
    finish_axes(ax1, "memory of every process, per cycle", legend_size=7)
    blocks = latency_blocks(rows, max(1, min(100, len(rows) // 10)))
    ax2.plot([b[0] for b in blocks], [b[1] for b in blocks], "o-", label="p50")
    ax2.plot([b[0] for b in blocks], [b[2] for b in blocks], "s-", label="p99")
    ax2.set_xlabel("cycle (first of each block)")
    ax2.set_ylabel("regulator -> finger A joint_states (us)")
    finish_axes(ax2, "latency per block of cycles")
    fig.tight_layout()
    fig.savefig(path, dpi=100)


def write_doc(doc, rows, lines, failed, warnings, processes, command, setup):
    png = doc.with_name(doc.stem.lower() + ".png")
    plot(rows, processes, png)
    blocks = latency_blocks(rows)
    p99 = [b[2] for b in blocks]
    trend = ""
    if len(p99) >= 3:
        n = len(p99)
        mean_x, mean_y = (n - 1) / 2, sum(p99) / n
        slope = sum((i - mean_x) * (y - mean_y) for i, y in enumerate(p99)) / sum((i - mean_x) ** 2 for i in range(n))
        trend = (f"p99 trend: {slope:+.0f} us per 100 cycles (least squares over the blocks), against a spread of "
                 f"{max(p99) - min(p99):.0f} us between blocks")
    cpu = subprocess.run(["lscpu"], capture_output=True, text=True).stdout
    model = re.search(r"Model name:\s*(.*)", cpu)
    text = [f"# A long run of the cell: {len(rows)} cycles", "",
            f"Measured by `{command}` on this machine ({os.cpu_count()} cores, {model.group(1) if model else 'unknown'}),"
            f" {time.strftime('%Y-%m-%d')}: the cell headless at a {setup} (the cell waits for the gripper where the"
            " fill outlasts the grasp phase; the sequencer asks the grip the part and the lift need). Every figure"
            " below is the script's; the verdicts are computed by it, not typed.", "",
            f"![memory of every process and latency per block of cycles]({png.name})", "", "```"]
    text += lines
    text += ["latency, regulator publish -> finger A joint_states at a subscriber, per 100 cycles "
             "(first cycle: median p50 / largest p99, us):"]
    text += [f"  {c:5d}: {a:7.0f} / {b:7.0f}" for c, a, b in blocks]
    if trend:
        text.append(trend)
    text.append(f"warnings on /rosout: {rows[-1]['warnings'] if rows else 0}; errors: {rows[-1]['errors'] if rows else 0}")
    text += [f"  {w}" for w in warnings[:10]]
    text.append("verdict: " + ("every check passed" if not failed else "FAILED: " + "; ".join(failed)))
    text += ["```", "", "The CSV of every cycle is `build/soak_cell.csv` (one row per cycle: time, outcome, warnings, "
             "latency p50/p99, each process's RSS and CPU seconds). The 50-cycle version runs with the tests "
             "(`test/test_soak.py`)."]
    doc.write_text("\n".join(text) + "\n")


def doc_option(doc):
    """The --doc option soak_cell.sh needs to write @p doc (none for its default, docs/SOAK.md)."""
    rel = os.path.relpath(pathlib.Path(doc).resolve(), ROOT)
    return "" if rel == "docs/SOAK.md" else f" --doc {rel}"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("cycles", type=int)
    parser.add_argument("--csv", default=str(ROOT / "build" / "soak_cell.csv"))
    parser.add_argument("--doc", help="write this page (docs/SOAK.md) and its plot beside it")
    parser.add_argument("--max-rss-growth-mb", type=float, default=1.0)
    parser.add_argument("--cycle-time", type=float, default=2.0, help="s (default 2, the shortest the schedule takes)")
    parser.add_argument("--object-mass", type=float, default=0.003, help="kg (default 0.003)")
    args = parser.parse_args()
    if args.cycles < 1:
        sys.exit("soak_cell: CYCLES must be a whole number >= 1")
    rows, warnings, processes = run(args.cycles, args.csv, args.cycle_time, args.object_mass)
    lines, failed = verdicts(rows, args.cycles, args.max_rss_growth_mb, processes)
    print("\n".join(lines))
    if args.doc:
        setup = f"{args.cycle_time:g} s cycle with a {1e3 * args.object_mass:g} g part"
        extra = "" if (args.cycle_time, args.object_mass) == (2.0, 0.003) else \
            f" --cycle-time {args.cycle_time:g} --object-mass {args.object_mass:g}"
        write_doc(pathlib.Path(args.doc), rows, lines, failed, warnings, processes,
                  f"bash scripts/soak_cell.sh {args.cycles}{extra}{doc_option(args.doc)}", setup)
    if failed:
        sys.exit("soak_cell: " + "; ".join(failed))
    print(f"soak_cell: {len(rows)} cycles, every check passed")


if __name__ == "__main__":
    main()
