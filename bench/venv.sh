# Sourced by the benchmark scripts: installs a requirements file into a virtual environment,
# again only when the file changed since the last successful install.
# Needs: a `log` function, $VENV (an existing venv) and $REQ (the requirements file).
install_requirements() {
    local stamp="$VENV/.requirements.sha256"
    local want
    want="$(sha256sum "$REQ" | cut -d' ' -f1)"
    if [[ ! -f "$stamp" || "$(cat "$stamp")" != "$want" ]]; then
        log "installing pinned requirements into $VENV"
        if ! "$VENV/bin/python" -m pip install --disable-pip-version-check -q -r "$REQ" >&2; then
            log "ERROR: 'pip install -r $REQ' failed (see pip output above)."
            exit 2
        fi
        echo "$want" > "$stamp"
    else
        log "reusing venv $VENV (requirements unchanged)"
    fi
}
