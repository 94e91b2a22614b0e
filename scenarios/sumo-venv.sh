# Sourced by the SUMO fixtures' generate.sh scripts: puts Eclipse SUMO 1.28.0
# (from PyPI, in a virtual environment) first on PATH and sets SUMO_HOME.
# SUMO_VENV overrides the venv, default /tmp/sumo-venv.
VENV=${SUMO_VENV:-/tmp/sumo-venv}
if [ ! -x "$VENV/bin/sumo" ]; then
    python3 -m venv "$VENV"
    "$VENV/bin/pip" install eclipse-sumo==1.28.0
fi
export PATH="$VENV/bin:$PATH"
SUMO_HOME=$("$VENV/bin/python" -c 'import sumo; print(sumo.SUMO_HOME)')
export SUMO_HOME
version=$(sumo --version)
[[ $version == *"sumo 1.28.0"* ]] || { echo "expected SUMO 1.28.0, found: ${version%%$'\n'*}" >&2; exit 1; }
