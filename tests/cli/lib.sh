# The preamble the CLI test scripts share, sourced with their arguments:
#   . "$(dirname "$0")/lib.sh" RELIEF SOURCE_DIR WORK_DIR
# sets relief (an absolute path), src and work, status=0, and gives
#   fail MESSAGE       prints FAIL: MESSAGE and makes the script's exit status 1
#   needs_povray       skips the test (exit 77, ctest's SKIP_RETURN_CODE) without POV-Ray
#   enter_fresh_work   makes WORK_DIR anew, empty, and enters it
set -u
relief=$(realpath "$1") src=$2 work=$3
status=0
fail() { echo "FAIL: $*"; status=1; }
needs_povray() { command -v povray >/dev/null || { echo "SKIP: povray is not installed"; exit 77; }; }
enter_fresh_work() { rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1; }
