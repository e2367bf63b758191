"""Counts test cases in catkin's JUnit XML results: 'tests: N passed, M failed, K skipped'.

catkin_test_results sums the `tests` attribute of gtest's <testsuites> root and of every <testsuite>, so it
reports each gtest case twice; this counts <testcase> elements instead. Exit status: 1 when any failed or none ran.
"""
import pathlib
import sys
import xml.etree.ElementTree as ET

passed = failed = skipped = 0
failed_names = []
for path in sorted(pathlib.Path(sys.argv[1]).rglob("*.xml")):
    root = ET.parse(path).getroot()
    for case in root.iter("testcase"):
        name = f"{case.get('classname')}.{case.get('name')}"
        problem = case.find("failure") if case.find("failure") is not None else case.find("error")
        if problem is not None:
            failed += 1
            # The assertion's own words, so that a failure on a CI machine can be read without its logs.
            said = " ".join((problem.get("message", "") + " " + (problem.text or "")).split())[:800]
            failed_names.append(f"{path.name}: {name}\n  {said}")
        elif case.find("skipped") is not None or case.get("status") == "notrun":
            skipped += 1
        else:
            passed += 1
for name in failed_names:
    print(f"FAILED {name}")
print(f"tests: {passed} passed, {failed} failed, {skipped} skipped")
sys.exit(1 if failed or passed == 0 else 0)
