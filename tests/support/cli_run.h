/* Runs the celadon CLI under test ($CELADON_BIN: the optimised or the
 * sanitized build) as a child process and captures what it prints. */
#ifndef CELADON_TEST_CLI_RUN_H
#define CELADON_TEST_CLI_RUN_H

typedef struct {
    int status; /* exit code */
    char *out;  /* everything written to stdout, NUL-terminated */
    /* everything written to stderr, NUL-terminated, but the learned prior's
     * once-a-run notice on a machine without its network ("celadon: the
     * learned object prior is off: ..."), which is counted instead: the
     * tests' one line per bad input holds on such a machine too */
    char *err;
    int prior_off_notices;
} cli_result;

/* The binary; skips the calling test when CELADON_BIN is not set. */
const char *cli_bin(void);

/* Runs `$CELADON_BIN args...` (args NULL-terminated), with its output captured
 * through files in scratch_dir. Fails the test if the child is killed by a
 * signal (a crash is never an acceptable answer to any input). */
cli_result cli_run(const char *scratch_dir, const char *const *args);
/* cli_run that also fails the test (and kills the child) when the command
 * has not finished after the given seconds: for inputs that used to hang. */
cli_result cli_run_within(const char *scratch_dir, const char *const *args, double seconds);
/* The same for any program: argv[0] is looked up in PATH (e.g. mpirun). */
cli_result cli_run_argv(const char *scratch_dir, const char *const *argv);
void cli_result_free(cli_result *r);

/* Starts `$CELADON_BIN args...` with stdout and stderr thrown away; its
 * process id (the caller waits for it). */
int cli_start_quiet(const char *const *args);

/* Sends sig to pid after delay seconds and waits for it; its wait status. */
int cli_signal_after(int pid, double delay, int sig);

/* Waits (at most limit seconds) until process pid has a handler for
 * signal sig (Linux: SigCgt in /proc/PID/status), so that a test's signal
 * is not the default action on a process still starting up. Returns 1 when
 * it has one. */
int cli_wait_for_handler(int pid, int sig, double limit);

/* The number of lines of printed text s (its newlines). */
int cli_count_lines(const char *s);

#endif
