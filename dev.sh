#!/usr/bin/env bash
# One entry point for set-up, the main job and the tests.
#   ./dev.sh demo     run the default workflow (embedded spur pair) -> results/
#   ./dev.sh test     the checks CI runs: ruff, the import layers (lint-imports) and every
#                     test, slow FE cases included; ./dev.sh test ARGS runs pytest ARGS only
#                     (the default selection leaves out the slow cases)
#   ./dev.sh bench    run the benchmark scripts in workflows/benchmarks
#   ./dev.sh chromium install Debian's headless Chromium if missing (the report's render test)
# The first call creates .venv and installs the package and its dependencies.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
cd "$here"
venv="$here/.venv"
stamp="$venv/.installed-$(sha256sum pyproject.toml | cut -c1-16)"

ensure_env() {
    if [ ! -f "$stamp" ]; then
        echo "[dev.sh] creating environment in .venv (first run only)" >&2
        python3 -m venv "$venv"
        # pip and setuptools' build backend print notices (editable-install warning box) on
        # stderr: keep them in a log and show it only when the install fails.
        log="$venv/install.log"
        if ! { "$venv/bin/python" -m pip install -q --upgrade pip \
               && "$venv/bin/python" -m pip install -q -e ".[test]"; } >"$log" 2>&1; then
            cat "$log" >&2
            echo "[dev.sh] installation failed; log kept in $log" >&2
            exit 1
        fi
        rm -f "$venv"/.installed-*
        touch "$stamp"
    fi
    export PATH="$venv/bin:$PATH"
    # Off-screen rendering for pyvista; one BLAS thread per process by default.
    export PYVISTA_OFF_SCREEN=true MPLBACKEND=Agg
    # Without a display, VTK's default X window warns before falling back to EGL: ask for EGL.
    if [ -z "${DISPLAY:-}" ]; then
        export VTK_DEFAULT_OPENGL_WINDOW="${VTK_DEFAULT_OPENGL_WINDOW:-vtkEGLRenderWindow}"
    fi
    export OMP_NUM_THREADS="${OMP_NUM_THREADS:-2}"
}

ensure_chromium() {
    # The slow report test renders the HTML report in headless Chromium (Debian's package).
    if ! command -v chromium >/dev/null 2>&1; then
        echo "[dev.sh] installing Debian's chromium (first run only)" >&2
        sudo_cmd=""
        if [ "$(id -u)" -ne 0 ]; then sudo_cmd="sudo"; fi
        $sudo_cmd apt-get update -q >&2
        DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -q --no-install-recommends \
            chromium fonts-dejavu-core >&2
    fi
    command -v chromium
}

cmd="${1:-help}"; shift || true
case "$cmd" in
    demo)  ensure_env; python workflows/default_case.py "$@" ;;
    test)  ensure_env
           if [ $# -eq 0 ]; then
               ruff check pipeline tests workflows
               lint-imports --no-cache >/dev/null || lint-imports --no-cache
               python -m pytest -m "slow or not slow"
           else
               python -m pytest "$@"
           fi ;;
    bench) ensure_env; for f in workflows/benchmarks/bench_*.py; do python "$f" "$@"; done ;;
    env)   ensure_env; echo "environment ready: $venv" ;;
    chromium) ensure_chromium ;;
    *)     sed -n '2,10p' "$0"; exit 2 ;;
esac
