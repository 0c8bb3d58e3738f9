# Sourced by the interruption tests (InterruptExport.sh, InterruptPieces.sh).
# run_and_record COMMAND...: runs COMMAND as a child of perl, writes the child's process id to
# launched.pid (the process a test sends its signal to) and, once it ends, how it ended to
# ending.txt: "signal N" or "exit N". A shell's own $? cannot tell a signal from an exit status
# above 128, and the test must know which.
run_and_record() {
  perl -e '
    my $pid = fork() // die "fork: $!";
    if ($pid == 0) { exec @ARGV or die "exec: $!" }
    open(my $p, ">", "launched.pid") or die; print $p $pid; close $p;
    waitpid($pid, 0);
    my $status = $?;
    open(my $e, ">", "ending.txt") or die;
    print $e (($status & 127) ? "signal " . ($status & 127) : "exit " . ($status >> 8)), "\n";
    close $e;
  ' -- "$@"
}

# signal_when_ready READY TRIES WHAT SIGNAL: polls the function READY every 0.05 s, up to TRIES
# times, then sends SIGNAL to the process run_and_record launched. Fails the test (exit 1) when
# that process ended before READY held, or READY never held, saying WHAT it waited for.
signal_when_ready() {
  local ready=$1 tries=$2 what=$3 signal=$4
  for _ in $(seq 1 "$tries"); do
    if "$ready"; then
      break
    fi
    if [ -e ending.txt ]; then
      echo "FAIL: cloudvis ended ($(cat ending.txt)) before $what" >&2
      cat stderr.txt >&2
      exit 1
    fi
    sleep 0.05
  done
  if ! "$ready"; then
    echo "FAIL: $what never came" >&2
    kill -KILL "$(cat launched.pid)"
    exit 1
  fi
  kill -s "$signal" "$(cat launched.pid)"
}
