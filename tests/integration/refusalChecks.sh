# Shared by the bad-input scripts (badInput.sh, badWaterInput.sh, badBendingInput.sh): copy the
# case, break one input, and expect the application to refuse it cleanly. The caller sets
# case_dir, work and app, calls `check`-style wrappers of these, and ends with `report`.
passed=0; failed=0

source "$(dirname "${BASH_SOURCE[0]}")/../../bin/caseCommon.sh"

# copy_broken_case NAME FILE EDIT: case_dir's constant/, system/ and DEM/ copied to work/NAME/case
# (with its own copy of cases/common at work/NAME/common), then FILE deleted (EDIT "delete") or
# edited in place by the sed expression EDIT, as are the common files FILE includes: an entry the
# case takes from cases/common is broken there.
copy_broken_case() {
    local name="$1" file="$2" edit="$3" case="$work/$1/case"
    rm -rf "$work/$name"; mkdir -p "$case"
    cp -r "$case_dir/constant" "$case_dir/system" "$case_dir/DEM" "$case/"
    copy_case_common "$case"
    if [ "$edit" = delete ]; then rm "$case/$file"; return; fi
    local included
    mapfile -t included < <(included_files "$case/$file")
    sed -i -e "$edit" "$case/$file" "${included[@]}"
}

# expect_refusal NAME EXPECTED [OPTIONS...]: app run on work/NAME (with OPTIONS) must exit non-zero,
# not by a signal (a crash), with EXPECTED in what it prints.
expect_refusal() {
    local name="$1" expected="$2"; shift 2
    local out rc
    out=$(mpirun -np 1 "$app" -case "$work/$name/case" "$@" 2>&1); rc=$?
    if [ $rc -ne 0 ] && [ $rc -lt 128 ] && grep -qF -- "$expected" <<<"$out"; then
        echo "ok   $name: $(grep -F -- "$expected" <<<"$out" | head -1 | sed 's/^ *//')"
        passed=$((passed + 1))
    else
        echo "FAIL $name (exit $rc), expected '$expected' in:"; echo "$out" | tail -5
        failed=$((failed + 1))
    fi
}

report() {
    echo "$passed passed, $failed failed"
    [ $failed -eq 0 ]
}
