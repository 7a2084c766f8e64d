# Sourced by the scripts that build ITK's wrapping, the wheel and run the Python tests.
# Venvs live outside the repository, under MESHEXTRACTION_CACHE (default
# ~/.cache/meshextraction); each is made from a pinned requirements file and made again
# when that file changes.

meshextraction_cache_dir() {
  echo "${MESHEXTRACTION_CACHE:-$HOME/.cache/meshextraction}"
}

# The Python that makes the venvs: CPython >= 3.11 with its headers (the limited API
# of PyPI's itk 5.4.7 wheels is 3.11's). MESHEXTRACTION_PYTHON overrides it.
meshextraction_base_python() {
  local python="${MESHEXTRACTION_PYTHON:-python3}"
  if ! "$python" -c 'import sys, sysconfig, os; sys.exit(not (sys.version_info >= (3, 11) and os.path.exists(os.path.join(sysconfig.get_paths()["include"], "Python.h"))))' 2>/dev/null; then
    echo "error: $python is not CPython >= 3.11 with its headers (Python.h); set MESHEXTRACTION_PYTHON" >&2
    return 1
  fi
  command -v "$python"
}

# meshextraction_venv NAME REQUIREMENTS_FILE: prints the venv's directory, making it if
# it is missing or was made from another version of the requirements.
meshextraction_venv() {
  local name="$1" requirements="$2"
  local venv
  venv="$(meshextraction_cache_dir)/$name"
  local stamp="$venv/.requirements"
  if [ -x "$venv/bin/python" ] && [ -f "$stamp" ] && cmp -s "$requirements" "$stamp"; then
    echo "$venv"
    return 0
  fi
  local python
  python="$(meshextraction_base_python)" || return 1
  echo "making the venv $venv from $requirements" >&2
  rm -rf "$venv"
  "$python" -m venv "$venv" >&2 || return 1
  "$venv/bin/python" -m pip install -q --upgrade pip >&2 || return 1
  "$venv/bin/python" -m pip install -q -r "$requirements" >&2 || return 1
  cp "$requirements" "$stamp"
  echo "$venv"
}

# The wrapped ITK tree the test command builds the wheel against when it is there:
# MESHEXTRACTION_ITK_PYTHON_DIR, or the fixed folder itk-v5.4.7-python of the cache
# (scripts/build-itk.sh ITK_SOURCE_DIR "$(meshextraction_cache_dir)/itk-v5.4.7-python").
meshextraction_wheel_itk_dir() {
  echo "${MESHEXTRACTION_ITK_PYTHON_DIR:-$(meshextraction_cache_dir)/itk-v5.4.7-python}"
}
