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
