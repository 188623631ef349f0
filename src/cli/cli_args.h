/* Argument handling shared by the subcommands. */
#ifndef CELADON_CLI_ARGS_H
#define CELADON_CLI_ARGS_H

/* Prints "celadon CMD: <fmt with arg> (try celadon CMD --help)" as one line on
 * stderr and returns 2, the exit code for bad usage. */
int cli_usage_error(const char *cmd, const char *fmt, const char *arg);

/* quiet 1: cli_usage_error prints nothing in this process (a rank of an
 * MPI job other than 0, where every rank would print the same line). */
void cli_set_quiet(int quiet);

/* The exit codes of every command (docs/faults.md): 0 done, 1 the outputs
 * could not be written (or another failure at run time), 2 bad input or
 * usage, 130 interrupted by Ctrl-C (render: the image so far was written). */
enum { CLI_OK = 0, CLI_CANNOT_WRITE = 1, CLI_BAD_INPUT = 2, CLI_INTERRUPTED = 130 };

/* Before the work: whether the output path (a file, or with is_folder a
 * folder) can be written (output_check). 0, or CLI_CANNOT_WRITE after one
 * line "celadon: PATH: cannot write there: REASON" (unless quiet). */
int cli_check_output(const char *path, int is_folder);

/* Whether the paths name the same existing file (under any names). */
int cli_same_file(const char *a, const char *b);

/* A whole decimal integer in [lo, hi]: 0, or -1 when s is anything else. */
int cli_parse_int(const char *s, long long lo, long long hi, long long *out);

/* A comma-separated list of 1..max whole integers, each in [lo, hi], into
 * out[0..*n): 0, or -1 when s is anything else. */
int cli_parse_int_list(const char *s, long long lo, long long hi, int *out, int max, int *n);

/* The -a folders of a scene's file search (Mitsuba's -a): at most this many. */
enum { CLI_MAX_SEARCH_DIRS = 64 };

/* -a's value: folders separated by ';' as Mitsuba takes them, each appended
 * (strndup'd: the caller frees them) to dirs[*n..CLI_MAX_SEARCH_DIRS). 0, or
 * the exit code (2 after a usage line naming cmd, 1 out of memory). */
int cli_add_search_dirs(const char *cmd, const char *val, char **dirs, int *n);

#endif
