#include "cli_run.h"

#include <criterion/criterion.h>
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

extern char **environ;

const char *cli_bin(void)
{
    const char *bin = getenv("CELADON_BIN");
    if (!bin || !*bin)
        cr_skip_test("CELADON_BIN is not set");
    return bin;
}

static char *slurp_and_remove(const char *path)
{
    FILE *f = fopen(path, "rb");
    cr_assert_not_null(f, "cannot read back %s", path);
    size_t cap = 4096, n = 0;
    char *buf = malloc(cap);
    cr_assert_not_null(buf);
    for (size_t k; (k = fread(buf + n, 1, cap - n - 1, f)) > 0;) {
        n += k;
        if (cap - n - 1 == 0) {
            cap *= 2;
            buf = realloc(buf, cap);
            cr_assert_not_null(buf);
        }
    }
    buf[n] = '\0';
    fclose(f);
    remove(path);
    return buf;
}

/* Takes the prior-off notice's lines out of r->err, counting them. */
static void set_aside_prior_notice(cli_result *r)
{
    static const char notice[] = "celadon: the learned object prior is off:";
    char *keep = r->err;
    for (const char *line = r->err; *line;) {
        const char *end = strchr(line, '\n');
        size_t len = end ? (size_t)(end - line) + 1 : strlen(line);
        if (!strncmp(line, notice, sizeof notice - 1)) {
            r->prior_off_notices++;
        } else {
            memmove(keep, line, len);
            keep += len;
        }
        line += len;
    }
    *keep = '\0';
}

/* Waits for pid, killing it after seconds (0: no limit); 0, or -1 when killed. */
static int wait_within(pid_t pid, double seconds, int *status)
{
    for (double waited = 0.0;; waited += 0.01) {
        pid_t got = waitpid(pid, status, seconds > 0.0 ? WNOHANG : 0);
        cr_assert_geq(got, 0);
        if (got == pid)
            return 0;
        if (waited >= seconds) {
            kill(pid, SIGKILL);
            waitpid(pid, status, 0);
            return -1;
        }
        usleep(10000);
    }
}

/* cli_run_argv, failing the test when the program has not finished after
 * seconds (0: no limit). */
static cli_result run_argv_within(const char *scratch_dir, const char *const *argv, double seconds)
{
    char out_path[512], err_path[512];
    snprintf(out_path, sizeof out_path, "%s/cli-stdout.txt", scratch_dir);
    snprintf(err_path, sizeof err_path, "%s/cli-stderr.txt", scratch_dir);
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 1, out_path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&fa, 2, err_path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    pid_t pid;
    cr_assert_eq(posix_spawnp(&pid, argv[0], &fa, NULL, (char *const *)argv, environ), 0, "cannot start %s",
                 argv[0]);
    posix_spawn_file_actions_destroy(&fa);
    int status;
    int killed = wait_within(pid, seconds, &status);
    cli_result r = {0, slurp_and_remove(out_path), slurp_and_remove(err_path), 0};
    set_aside_prior_notice(&r);
    cr_assert(!killed, "%s did not finish within %.0f s", argv[0], seconds);
    cr_assert(WIFEXITED(status), "%s died from signal %d; stderr: %s", argv[0],
              WIFSIGNALED(status) ? WTERMSIG(status) : 0, r.err);
    r.status = WEXITSTATUS(status);
    return r;
}

cli_result cli_run_argv(const char *scratch_dir, const char *const *argv)
{
    return run_argv_within(scratch_dir, argv, 0.0);
}

cli_result cli_run_within(const char *scratch_dir, const char *const *args, double seconds)
{
    size_t n = 0;
    while (args[n])
        n++;
    const char **argv = malloc((n + 2) * sizeof *argv);
    cr_assert_not_null(argv);
    argv[0] = cli_bin();
    memcpy(argv + 1, args, (n + 1) * sizeof *argv);
    cli_result r = run_argv_within(scratch_dir, argv, seconds);
    free(argv);
    return r;
}

cli_result cli_run(const char *scratch_dir, const char *const *args) { return cli_run_within(scratch_dir, args, 0.0); }

void cli_result_free(cli_result *r)
{
    free(r->out);
    free(r->err);
    r->out = r->err = NULL;
}

int cli_start_quiet(const char *const *args)
{
    const char *argv[64] = {cli_bin()};
    int n = 1;
    for (; *args && n < 63; args++)
        argv[n++] = *args;
    argv[n] = NULL;
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&fa, 2, "/dev/null", O_WRONLY, 0);
    pid_t pid;
    cr_assert_eq(posix_spawn(&pid, argv[0], &fa, NULL, (char *const *)argv, environ), 0);
    posix_spawn_file_actions_destroy(&fa);
    return pid;
}

int cli_signal_after(int pid, double delay, int sig)
{
    struct timespec ts = {(time_t)delay, (long)((delay - (time_t)delay) * 1e9)};
    nanosleep(&ts, NULL);
    kill(pid, sig);
    int status;
    cr_assert_eq(waitpid(pid, &status, 0), pid);
    return status;
}

int cli_count_lines(const char *s)
{
    int n = 0;
    for (; *s; s++)
        n += *s == '\n';
    return n;
}

int cli_wait_for_handler(int pid, int sig, double limit)
{
    char path[64], line[256];
    snprintf(path, sizeof path, "/proc/%d/status", pid);
    for (double t = 0; t < limit; t += 0.02) {
        FILE *f = fopen(path, "r");
        unsigned long long caught = 0;
        while (f && fgets(line, sizeof line, f))
            if (sscanf(line, "SigCgt: %llx", &caught) == 1)
                break;
        if (f)
            fclose(f);
        if (caught & (1ull << (sig - 1)))
            return 1;
        usleep(20000);
    }
    return 0;
}
