# Sourced by the scripts here that draw the documentation's pictures (make-guide-images.sh,
# make-viewer-images.sh): their options, their display and the cloudvis they run.

# read_options SPEC USAGE_LINES ARGUMENTS...: SPEC pairs each option letter with the variable its
# argument sets ("s=size d=dimensions"); -h prints the lines USAGE_LINES ("6,13") of the script,
# its usage comment, and exits; an unknown option prints them and exits with status 2. The
# operands after the options are left in the array `operands`.
read_options() {
  local spec=$1 lines=$2 letters="" pair option
  shift 2
  for pair in $spec; do
    letters+="${pair%%=*}:"
  done
  OPTIND=1
  while getopts "${letters}h" option; do
    case "$option" in
      h) sed -n "${lines}p" "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
      \?) sed -n "${lines}p" "$0" | sed 's/^# \{0,1\}//' >&2; exit 2 ;;
      *)
        for pair in $spec; do
          if [[ "${pair%%=*}" == "$option" ]]; then
            printf -v "${pair#*=}" '%s' "$OPTARG"
          fi
        done
        ;;
    esac
  done
  shift $((OPTIND - 1))
  operands=("$@")
}

# on_a_display ARGUMENTS...: without $DISPLAY, runs the script again under xvfb-run with the
# same arguments.
on_a_display() {
  if [[ -z "${DISPLAY:-}" ]]; then
    exec xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" "$0" "$@"
  fi
}

# require_cloudvis PATH: stops with a message unless PATH is an executable.
require_cloudvis() {
  if [[ ! -x "$1" ]]; then
    echo "$(basename "$0"): no cloudvis at $1 (build it first: make build)" >&2
    exit 1
  fi
}
