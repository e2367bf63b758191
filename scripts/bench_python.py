"""The Python API's calls timed as a designer makes them (scripts/benchmarks.py runs it beside finger_bench and puts
the figures side by side on docs/BENCHMARKS.md): 2 million pressures uniform over the validated range, the robust
solver, the shipped finger. Each figure is the fastest of REPETITIONS runs (this VM's neighbours only add time).

usage: python3 scripts/bench_python.py [REPETITIONS]     one JSON object on stdout
"""
import json
import sys
import time

import numpy

import pneumatic_finger.core as pf

COUNT = 2_000_000
VALIDATED_MAX_GAUGE_PA = 196133.0


def fastest(call, repetitions):
    times = []
    for _ in range(repetitions):
        start = time.perf_counter()
        call()
        times.append(time.perf_counter() - start)
    return min(times)


def main():
    repetitions = int(sys.argv[1]) if len(sys.argv) > 1 else 5
    model = pf.FingerModel()
    p = numpy.random.default_rng(2).uniform(0.0, VALIDATED_MAX_GAUGE_PA, COUNT)
    out = {k: numpy.empty_like(v) for k, v in model.evaluate(p[:1]).items() if k != "status"}
    out = {k: numpy.empty((COUNT,) + v.shape[1:], v.dtype) for k, v in out.items()}
    out["status"] = numpy.empty(COUNT, numpy.uint8)
    model.evaluate(p, out=out)  # the caller's arrays, touched once (as a sweep in chunks reuses them)
    disk = (0.075, 0.035, 0.01)
    contact_p = p[:200_000]
    designs = numpy.stack(numpy.meshgrid(numpy.linspace(0.008, 0.016, 1000), numpy.linspace(20e-6, 200e-6, 1000),
                                         indexing="ij"), axis=-1).reshape(-1, 2)
    cases = [
        ("tip_fresh", "Python evaluate(p, outputs=['tip_angle_rad']): tip angle only, fresh array", COUNT,
         lambda: model.evaluate(p, outputs=["tip_angle_rad"])),
        ("full_fresh", "Python evaluate(p): every output, fresh arrays", COUNT, lambda: model.evaluate(p)),
        ("full_out", "Python evaluate(p, out=...): every output, into the caller's arrays", COUNT,
         lambda: model.evaluate(p, out=out)),
        ("contact", "Python contact(p, disk): the finger on one disk, every output, fresh arrays", len(contact_p),
         lambda: model.contact(contact_p, disk)),
        ("designs", "Python sweep_designs: 1,000 x 1,000 designs (chamber_height_m x chamber_gap_m), tip angle at "
                    "2 kg/cm^2", len(designs),
         lambda: model.sweep_designs(["chamber_height_m", "chamber_gap_m"], designs, VALIDATED_MAX_GAUGE_PA,
                                     outputs=["tip_angle_rad"])),
    ]
    result = {}
    for key, label, count, call in cases:
        seconds = fastest(call, 1 if key == "designs" else repetitions)
        result[key] = {"label": label, "count": count, "seconds": seconds, "per_second": count / seconds}
    json.dump(result, sys.stdout, indent=1)
    print()


if __name__ == "__main__":
    main()
