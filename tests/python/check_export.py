"""Runs the ASAM Quality Checker on an export of `sightline export`: the
OpenDRIVE bundle (asam-qc-opendrive) on the map and the OpenSCENARIO bundle
(asam-qc-openscenarioxml) on the scenario, each headless from a generated
configuration file, and reads their result files (.xqar).

Usage: python check_export.py DIR  (DIR holds scenario.xosc and scenario.xodr)

Prints every issue as `LEVEL checker: description` and one summary line per
bundle; exits 1 when an issue has level ERROR, when a checker ended in error
(it crashed), or when a checker the bundle registers was skipped because its
preconditions failed (a file that is not valid XML, a schema error): every
checker applicable to the written version must have run.
"""

import pathlib
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

# qc_baselib's IssueSeverity: 1 error, 2 warning, 3 information.
LEVELS = {"1": "ERROR", "2": "WARNING", "3": "INFORMATION"}

BUNDLES = [
    ("qc_opendrive", "xodrBundle", "scenario.xodr"),
    ("qc_openscenario", "xoscBundle", "scenario.xosc"),
]


def run_bundle(tool: pathlib.Path, application: str, input_file: pathlib.Path, work: pathlib.Path) -> bool:
    result_file = work / f"{application}.xqar"
    config = work / f"{application}.xml"
    root = ET.Element("Config")
    ET.SubElement(root, "Param", name="InputFile", value=str(input_file))
    bundle = ET.SubElement(root, "CheckerBundle", application=application)
    ET.SubElement(bundle, "Param", name="resultFile", value=str(result_file))
    ET.ElementTree(root).write(config, encoding="UTF-8", xml_declaration=True)
    run = subprocess.run([str(tool), "-c", str(config)], capture_output=True, text=True)
    if run.returncode != 0 or not result_file.exists():
        print(f"{application}: the checker failed (exit {run.returncode}):\n{run.stdout}{run.stderr}")
        return False
    ok = True
    counts = {"ERROR": 0, "WARNING": 0, "INFORMATION": 0}
    ran = skipped = 0
    for checker in ET.parse(result_file).getroot().iter("Checker"):
        status = checker.get("status")
        name = checker.get("checkerId")
        summary = checker.get("summary", "")
        if status == "error":
            print(f"ERROR {name}: the checker ended in error: {summary}")
            ok = False
        elif status == "skipped":
            skipped += 1
            # Checks defined for a later version than the file's are skipped
            # by design; anything else (a failed precondition) is a failure.
            if "definition setting" not in summary:
                print(f"ERROR {name}: skipped: {summary}")
                ok = False
        else:
            ran += 1
        for issue in checker.iter("Issue"):
            level = LEVELS.get(issue.get("level"), issue.get("level"))
            counts[level] = counts.get(level, 0) + 1
            print(f"{level} {name}: {issue.get('description')}")
            if level == "ERROR":
                ok = False
    print(
        f"{application}: {input_file.name}: {ran} checks run, {skipped} skipped for the file's version; "
        f"{counts['ERROR']} errors, {counts['WARNING']} warnings, {counts['INFORMATION']} information"
    )
    return ok


def main() -> int:
    if len(sys.argv) != 2:
        print(__doc__)
        return 2
    directory = pathlib.Path(sys.argv[1]).resolve()
    bin_dir = pathlib.Path(sys.executable).parent
    ok = True
    with tempfile.TemporaryDirectory() as work:
        for tool, application, name in BUNDLES:
            ok &= run_bundle(bin_dir / tool, application, directory / name, pathlib.Path(work))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
