# Sourced by the tool's case scripts: expect_failure NAME TEXT COMMAND... runs COMMAND
# (60 s at most: a hang is a failure), and passes when it exits non-zero and its output
# holds TEXT (a grep -E pattern). Failures are counted; `finish` exits 1 if any.
failures=0
expect_failure() {
    local name=$1 text=$2 out rc
    shift 2
    set +e
    out=$(timeout 60 "$@" 2>&1)
    rc=$?
    set -e
    if [[ $rc -eq 0 ]]; then
        echo "FAIL $name: exit 0 (expected a failure saying: $text)"; failures=$((failures + 1))
    elif [[ $rc -eq 124 ]]; then
        echo "FAIL $name: hung (killed after 60 s)"; failures=$((failures + 1))
    elif ! grep -qE -- "$text" <<< "$out"; then
        echo "FAIL $name: exit $rc, but the output lacks '$text':"; echo "$out" | tail -n 5; failures=$((failures + 1))
    else
        echo "ok   $name: $(grep -E -m1 -- "$text" <<< "$out")"
    fi
}
finish() {
    echo "$failures case(s) failed"
    [[ $failures -eq 0 ]]
}
