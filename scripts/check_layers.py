"""Checks that each layer includes only what its folder allows: the core, the calibration room, the description, the sim
layer and the tools never see a ROS header, and only the calibration room sees the solvers (Ceres, NLopt). On Debian the ROS
headers live in /usr/include beside every other library's, so the compiler cannot enforce this; this script does, from
the #include lines.

usage: python3 scripts/check_layers.py [ROOT]      exit 1 and one line per violation
       python3 scripts/check_layers.py --self-test  shows that a ROS include in the core is caught
"""
import pathlib
import re
import sys
import tempfile

# What a ROS-free layer may include besides the C++ standard library and its own internal headers (a file beside it
# in the same folder): its own layer and the ones below it, Eigen, yaml-cpp, the compiler's SIMD intrinsics (core
# only), urdfdom (description only), CLI11 (tools only), pybind11 (the Python module only), POSIX.
ALLOWED = {
    "core": [r"pneumatic_finger/core/", r"Eigen/", r"yaml-cpp/", r"immintrin\.h$"],
    "description": [r"pneumatic_finger/(core|description)/", r"Eigen/", r"yaml-cpp/", r"urdf_model/", r"urdf_parser/",
                    r"urdf_world/", r"tinyxml\.h"],
    "sim": [r"pneumatic_finger/(core|description|sim)/", r"Eigen/", r"yaml-cpp/", r"urdf_model/", r"urdf_parser/",
            r"urdf_world/", r"mujoco/"],
    "calibration": [r"pneumatic_finger/(core|calibration)/", r"Eigen/", r"ceres/", r"nlopt\.hpp$"],
    "tools": [r"pneumatic_finger/(core|calibration|description|sim|tools)/", r"Eigen/", r"CLI/", r"unistd\.h"],
    "python": [r"pneumatic_finger/(core|calibration)/", r"Eigen/", r"pybind11/"],
}
# What a ROS layer may not include: the layers above it. The cell is built over src/ros (its regulator, sequencer and
# nodelets), so src/ros never includes the cell.
FORBIDDEN = {
    "ros": [r"pneumatic_finger/cell/"],
}
INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]([^>"]+)[>"]')


def is_standard(header):
    # The C++ standard headers have no extension and no folder; the C ones are <cxxx>.
    return "/" not in header and "." not in header


def violations(root):
    found = []
    for layer, allowed in ALLOWED.items():
        for folder in (root / "include" / "pneumatic_finger" / layer, root / "src" / layer):
            for path in sorted(folder.rglob("*")):
                if path.suffix not in (".hpp", ".h", ".cpp"):
                    continue
                for number, line in enumerate(path.read_text().splitlines(), 1):
                    m = INCLUDE.match(line)
                    header = m.group(1) if m else ""
                    beside = "/" not in header and (path.parent / header).is_file()  # the layer's internal header
                    if not m or is_standard(header) or beside:
                        continue
                    if not any(re.match(a, m.group(1)) for a in allowed):
                        found.append(f"{path.relative_to(root)}:{number}: layer '{layer}' may not include "
                                     f"<{m.group(1)}>")
    for layer, forbidden in FORBIDDEN.items():
        for folder in (root / "include" / "pneumatic_finger" / layer, root / "src" / layer):
            for path in sorted(folder.rglob("*")) if folder.is_dir() else []:
                if path.suffix not in (".hpp", ".cpp", ".h"):
                    continue
                for number, line in enumerate(path.read_text().splitlines(), 1):
                    m = INCLUDE.match(line)
                    if m and any(re.match(f, m.group(1)) for f in forbidden):
                        found.append(f"{path.relative_to(root)}:{number}: layer '{layer}' may not include "
                                     f"<{m.group(1)}> (a layer above it)")
    return found


def self_test():
    with tempfile.TemporaryDirectory() as tmp:
        root = pathlib.Path(tmp)
        (root / "src" / "core").mkdir(parents=True)
        (root / "src" / "core" / "bad.cpp").write_text('#include <cmath>\n#include <ros/ros.h>\n')
        (root / "src" / "ros").mkdir(parents=True)
        (root / "src" / "ros" / "up.cpp").write_text('#include "pneumatic_finger/cell/pressure_regulator.hpp"\n')
        got = violations(root)
        ok = got == ["src/core/bad.cpp:2: layer 'core' may not include <ros/ros.h>",
                     "src/ros/up.cpp:1: layer 'ros' may not include <pneumatic_finger/cell/pressure_regulator.hpp> "
                     "(a layer above it)"]
        print("check_layers self-test:", "ok" if ok else f"FAILED, got {got}")
        return 0 if ok else 1


if __name__ == "__main__":
    if sys.argv[1:] == ["--self-test"]:
        sys.exit(self_test())
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parent.parent)
    bad = violations(root)
    for b in bad:
        print(b)
    print(f"check_layers: {len(bad)} violation(s) in core, calibration, description, sim, tools, python and ros")
    sys.exit(1 if bad else 0)
