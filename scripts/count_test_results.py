#!/usr/bin/env python3
"""Sums up the JUnit XML files that catkin's run_tests leaves in build/test_results.

Prints each failed or errored test case, then one line "N passed, N failed"
(skipped cases are reported after it when there are any). Exits 1 if any
case failed, or if no result file or no test case was found at all.
"""
import glob
import os
import sys
import xml.etree.ElementTree as ET


def main(results_dir):
    files = sorted(glob.glob(os.path.join(results_dir, "**", "*.xml"), recursive=True))
    passed = failed = skipped = 0
    for path in files:
        try:
            root = ET.parse(path).getroot()
        except ET.ParseError as exc:
            print("unreadable result file %s: %s" % (path, exc))
            failed += 1
            continue
        cases = root.iter("testcase")
        for case in cases:
            name = "%s.%s" % (case.get("classname", "?"), case.get("name", "?"))
            if case.find("failure") is not None or case.find("error") is not None:
                failed += 1
                node = case.find("failure") if case.find("failure") is not None else case.find("error")
                text = (node.get("message") or node.text or "").strip().splitlines()
                print("FAILED %s (%s): %s" % (name, os.path.basename(path), text[0] if text else ""))
            elif case.find("skipped") is not None or case.get("status") == "notrun":
                skipped += 1
            else:
                passed += 1
    if not files or passed + failed == 0:
        print("no test results found in %s" % results_dir)
        failed = max(failed, 1)
    line = "%d passed, %d failed" % (passed, failed)
    if skipped:
        line += ", %d skipped" % skipped
    print(line)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "build/test_results"))
