# Sourced by every Allrun (and the Allcleans that take options): strict option
# checks, as the applications' CommandLine does. Each check names the option and
# what it allows; a failed check is a usage error: `Allrun: <message>` and the
# script's usage line on stderr, exit status 2, before the script writes anything.
# The usage line is the script's `# Usage: ./Allrun ...` header comment (up to
# two spaces in a row), so it is written once.
#
#   while [ $# -gt 0 ]; do
#       case "$1" in
#           -np) need_value "$@"; whole_number -np "$2" 1 "$maxRanks"; np="$2"; shift 2 ;;
#           -smoke) smoke=yes; shift ;;
#           *) unknown_option "$1" ;;
#       esac
#   done

maxRanks=64     # -np: more ranks than this on one machine is a typing error

# The sourcing Allrun: its path as invoked, or (when it has cd'ed into its own
# folder since, as most do) its name there.
allrunScript="${BASH_SOURCE[1]:-}"
[ -f "$allrunScript" ] || allrunScript="$(basename "$allrunScript")"

# The usage line of the Allrun's header: "usage: ./Allrun [...]".
allrun_usage() {
    local line
    line="$(sed -n 's/^#.*Usage:[[:space:]]*//p' "$allrunScript" 2>/dev/null | head -1)"
    line="${line%%  *}"
    echo "usage: ${line:-./$(basename "$allrunScript") (see the header of $allrunScript)}"
}

# usage_error MESSAGE: the message and the usage line on stderr, exit 2.
usage_error() {
    echo "$(basename "$allrunScript"): $1" >&2
    allrun_usage >&2
    exit 2
}

# unknown_option OPTION
unknown_option() {
    usage_error "$1: unknown option"
}

# need_value OPTION [VALUE ...]: call as `need_value "$@"` in the option loop;
# refuses a missing value or one that starts with '-' (the next option).
need_value() {
    [ $# -ge 2 ] || usage_error "$1: needs a value"
    case "$2" in
        -*) usage_error "$1: needs a value, got the option '$2'" ;;
        "") usage_error "$1: needs a non-empty value" ;;
    esac
}

# whole_number OPTION VALUE MIN [MAX]: VALUE, the whole string, a whole number
# from MIN (to MAX).
whole_number() {
    local option="$1" value="$2" min="$3" max="${4:-}" range n
    if [ -n "$max" ]; then range="from $min to $max"; else range="of at least $min"; fi
    n="${value#"${value%%[!0]*}"}"    # leading zeros off (bash reads 010 as octal)
    [[ "$value" =~ ^[0-9]+$ ]] && [ ${#n} -le 15 ] && [ "${n:-0}" -ge "$min" ] \
        && { [ -z "$max" ] || [ "${n:-0}" -le "$max" ]; } \
        || usage_error "$option: needs a whole number $range, got '$value'"
}

# positive_number OPTION VALUE: VALUE, the whole string, a decimal number > 0
# (0.2, 5e-3; not 0, -1, 1e3x, inf).
positive_number() {
    [[ "$2" =~ ^\+?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][-+]?[0-9]+)?$ ]] && [[ "${BASH_REMATCH[1]}" =~ [1-9] ]] \
        || usage_error "$1: needs a positive number, got '$2'"
}

# choice OPTION VALUE a|b|c: VALUE one of the words.
choice() {
    local word
    local IFS='|'
    for word in $3; do
        [ "$2" = "$word" ] && return 0
    done
    usage_error "$1: needs one of $3, got '$2'"
}

# choice_list OPTION VALUE SEPARATOR a|b|c: VALUE a non-empty list of the words
# (-keels "cuboid empirical": separator ' '; --only E1,E4: ',').
choice_list() {
    local option="$1" value="$2" sep="$3" allowed="$4" item
    local -a items
    IFS="$sep" read -r -a items <<< "$value"
    [ "$sep" != , ] || [[ "$value" =~ ^[^,]+(,[^,]+)*$ ]] || items=()
    [ ${#items[@]} -gt 0 ] || usage_error "$option: needs a list of $allowed, got '$value'"
    for item in "${items[@]}"; do
        ( choice "$option" "$item" "$allowed" ) 2>/dev/null \
            || usage_error "$option: needs a list of $allowed (separated by '$sep'), got '$value'"
    done
}

# number_list OPTION VALUE MIN MAX: VALUE comma-separated whole numbers from MIN to MAX (1,2,5).
number_list() {
    local option="$1" value="$2" item
    local -a items
    [[ "$value" =~ ^[0-9]+(,[0-9]+)*$ ]] \
        || usage_error "$option: needs comma-separated whole numbers from $3 to $4, got '$value'"
    IFS=, read -r -a items <<< "$value"
    for item in "${items[@]}"; do
        ( whole_number "$option" "$item" "$3" "$4" ) 2>/dev/null \
            || usage_error "$option: needs comma-separated whole numbers from $3 to $4, got '$value'"
    done
}

# options_parsed: call after the option loop (and the checks between options),
# before the Allrun checks for its applications or touches a file. With
# ALLRUN_CHECK_ONLY=1 in the environment the Allrun stops there with status 0:
# the top-level ./Allrun checks its options so before its install and build,
# and tests/cases/allrunOptions.sh checks valid command lines so.
options_parsed() {
    [ -z "${ALLRUN_CHECK_ONLY:-}" ] || exit 0
}
