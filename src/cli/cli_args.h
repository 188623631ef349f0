/* Argument handling shared by the subcommands. */
#ifndef CELADON_CLI_ARGS_H
#define CELADON_CLI_ARGS_H

/* Prints "celadon CMD: <fmt with arg> (try celadon CMD --help)" as one line on
 * stderr and returns 2, the exit code for bad usage. */
int cli_usage_error(const char *cmd, const char *fmt, const char *arg);

/* quiet 1: cli_usage_error prints nothing in this process (a rank of an
 * MPI job other than 0, where every rank would print the same line). */
void cli_set_quiet(int quiet);

/* A whole decimal integer in [lo, hi]: 0, or -1 when s is anything else. */
int cli_parse_int(const char *s, long long lo, long long hi, long long *out);

/* A comma-separated list of 1..max whole integers, each in [lo, hi], into
 * out[0..*n): 0, or -1 when s is anything else. */
int cli_parse_int_list(const char *s, long long lo, long long hi, int *out, int max, int *n);

#endif
