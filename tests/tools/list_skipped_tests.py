#!/usr/bin/env python3
"""Lists the tests CTest skipped, each with the reason the test printed, from the JUnit file of
`ctest --output-junit FILE` (./run.sh test writes build/Testing/ctest-junit.xml). A skip is a
test that could not run (a tool, package or shared asset missing): it proves nothing, so CI
shows which ones and why. Exit 0 whatever was skipped; 2 when the file cannot be read.

The reason is the test's own line: the ANIMORPH_SKIP marker of a Catch2 case
(tests/util/test_skip.h), or the line of a script that exited 77 ("SKIP: ...", "... skipped").

usage: list_skipped_tests.py JUNIT_XML"""
import re
import sys
import xml.etree.ElementTree as ET

MARKER = "ANIMORPH_TEST_SKIPPED:"  # tests/util/test_skip.h


def skip_reason(output, how):
    """The line of the test's output that says why it skipped; CTest's own account (the exit code or
    the matched expression) when no line does."""
    lines = [l.strip() for l in (output or "").splitlines() if l.strip()]
    for line in lines:
        if MARKER in line:
            return line.split(MARKER, 1)[1].strip()
    for line in lines:
        if re.search(r"\bskip(ped)?\b", line, re.IGNORECASE):
            return line
    return how or "no reason printed"


def skipped_tests(path):
    """[(test name, reason)] of the tests that did not run, in the order CTest ran them."""
    root = ET.parse(path).getroot()
    found = []
    for case in root.iter("testcase"):
        skipped = case.find("skipped")
        if skipped is None and case.get("status") not in ("notrun", "disabled"):
            continue
        how = skipped.get("message", "") if skipped is not None else case.get("status", "")
        out = case.find("system-out")
        found.append((case.get("name", "?"), skip_reason(out.text if out is not None else "", how)))
    return found


def main():
    if len(sys.argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    try:
        found = skipped_tests(sys.argv[1])
    except (OSError, ET.ParseError) as e:
        print(f"list_skipped_tests: cannot read {sys.argv[1]}: {e}", file=sys.stderr)
        return 2
    if not found:
        print("Skipped tests: none")
        return 0
    print(f"Skipped tests ({len(found)}; each could not run, and proves nothing):")
    for name, reason in found:
        print(f"  SKIPPED {name}: {reason}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
