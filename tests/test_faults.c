/* Faults (issue 15, docs/faults.md): SIGINT and SIGTERM at moments spread
 * over a render and over a batch reconstruct leave complete outputs or
 * none, and never a temporary; a full disk (a small tmpfs, where the test
 * may mount one) leaves nothing half-written and exits 1. */
#include <criterion/criterion.h>
#include <dirent.h>
#include <fcntl.h>
#include <ftw.h>
#include <pthread.h>
#include <signal.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "celadon/image.h"
#include "celadon/profile.h"
#include "core/core.h"
#include "support/cli_run.h"
#include "support/scratch_dir.h"
#include "support/synth_vessel.h"

extern char **environ;

static char dir[256];

static void open_dir(void) { scratch_dir_make(dir, sizeof dir, "faults"); }
static void close_dir(void) { scratch_dir_remove(dir); }

TestSuite(faults, .init = open_dir, .fini = close_dir);

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/* Starts celadon ARGS with its output thrown away. */
static pid_t start(const char *const *args) { return cli_start_quiet(args); }

/* Runs celadon ARGS to the end; its wall time, seconds. */
static double time_run(const char *const *args)
{
    double t0 = now();
    int status;
    cr_assert_eq(waitpid(start(args), &status, 0) > 0, 1);
    cr_assert(WIFEXITED(status) && WEXITSTATUS(status) == 0, "the uninterrupted run failed (status %d)", status);
    return now() - t0;
}

/* Runs celadon ARGS, sends sig after delay seconds; the wait status. */
static int run_interrupted(const char *const *args, double delay, int sig)
{
    return cli_signal_after(start(args), delay, sig);
}

static int temporaries;

static int is_temporary(const char *name)
{
    return strstr(name, ".tmp-") || strstr(name, ".celadon-tmp-") || strstr(name, ".celadon-museum-");
}

static int count_temporary(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
    (void)st, (void)flag;
    if (is_temporary(path + ftw->base)) {
        cr_log_error("left behind: %s", path);
        temporaries++;
    }
    return 0;
}

/* Temporaries anywhere under root. */
static int temporaries_under(const char *root)
{
    temporaries = 0;
    nftw(root, count_temporary, 16, FTW_PHYS);
    return temporaries;
}

static int remove_entry(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
    (void)st, (void)flag, (void)ftw;
    return remove(path);
}

static void remove_tree(const char *path) { nftw(path, remove_entry, 16, FTW_DEPTH | FTW_PHYS); }

/* Whatever exit: 128 + the signal from render's own handler (its image
 * written), death by the signal, or 0 when the signal came after the work;
 * never a crash of another kind. */
static void expect_signal_outcome(int status, int sig)
{
    cr_expect((WIFEXITED(status) && (WEXITSTATUS(status) == 0 || WEXITSTATUS(status) == 128 + sig)) ||
                  (WIFSIGNALED(status) && WTERMSIG(status) == sig),
              "signal %d gave status %#x", sig, status);
}

/* The delays: spread over the uninterrupted run's time t, the last ones
 * near its end, where the outputs are written. */
#define TRIALS 8
static double delay_of(int k, double t)
{
    static const double at[TRIALS] = {0.05, 0.3, 0.55, 0.75, 0.85, 0.92, 0.97, 1.0};
    return at[k] * t;
}

static const char scene_xml[] =
    "<scene version=\"3.0.0\"><sensor type=\"perspective\"><transform name=\"to_world\">"
    "<lookat origin=\"0,0,4\" target=\"0,0,0\" up=\"0,1,0\"/></transform></sensor>"
    "<emitter type=\"constant\"><rgb name=\"radiance\" value=\"1,1,1\"/></emitter>"
    "<shape type=\"sphere\"><bsdf type=\"diffuse\"/></shape></scene>\n";

static void write_scene(char *path, size_t len) { scratch_write_file(dir, "scene.xml", scene_xml, path, len); }

Test(faults, signals_during_a_render_leave_the_image_whole_or_none, .timeout = 300)
{
    char scene[300], out_dir[300], out[320];
    write_scene(scene, sizeof scene);
    snprintf(out_dir, sizeof out_dir, "%s/render", dir);
    for (int k = 0; k < 2 * TRIALS + 1; k++) {
        const char *ext = k % 2 ? "exr" : "png";
        remove_tree(out_dir);
        cr_assert_eq(mkdir(out_dir, 0777), 0);
        snprintf(out, sizeof out, "%s/out.%s", out_dir, ext);
        const char *args[] = {"render", scene, "-o", out, "--res", "64x64", "--spp", "32", NULL};
        static double t;
        if (k == 0) {
            t = time_run(args);
            continue;
        }
        int sig = k % 4 < 2 ? SIGINT : SIGTERM;
        expect_signal_outcome(run_interrupted(args, delay_of((k - 1) / 2, t), sig), sig);
        cr_expect_eq(temporaries_under(out_dir), 0, "after signal %d at %.2f s", sig, delay_of((k - 1) / 2, t));
        if (access(out, F_OK) == 0) {
            image_t img;
            char why[512];
            cr_expect_eq(image_read(out, &img, why, sizeof why), 0, "%s is not whole: %s", out, why);
            if (img.data)
                cr_expect(img.width == 64 && img.height == 64);
            image_free(&img);
        }
    }
}

static void draw_photo(const char *name, synth_shape shape, int width, int height)
{
    synth_params p = synth_defaults(shape, width, height);
    p.textured = 1;
    p.subrows = 4;
    image_t img;
    cr_assert_eq(synth_draw(&p, &img), 0);
    char path[320], err[256];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    cr_assert_eq(synth_write(path, &img, 8, err, sizeof err), 0, "%s", err);
    image_free(&img);
}

/* Every folder of a batch's output holds the six outputs, whole. */
static void expect_whole_vessels(const char *out)
{
    DIR *d = opendir(out);
    if (!d)
        return;
    for (struct dirent *e; (e = readdir(d));) {
        if (e->d_name[0] == '.')
            continue;
        char sub[600], path[700], err[512];
        snprintf(sub, sizeof sub, "%s/%s", out, e->d_name);
        int n = 0;
        DIR *s = opendir(sub);
        cr_assert_not_null(s, "%s is not a folder", sub);
        for (struct dirent *f; (f = readdir(s));)
            n += f->d_name[0] != '.';
        closedir(s);
        cr_expect_eq(n, 6, "%s holds %d files, not the six outputs", sub, n);
        snprintf(path, sizeof path, "%s/profile.json", sub);
        profile_t p;
        if (n == 6) {
            int rc = profile_read_json(path, &p, err, sizeof err);
            cr_expect_eq(rc, 0, "%s: %s", path, err);
            if (rc == 0)
                profile_free(&p);
        }
    }
    closedir(d);
}

/* A batch of two photos (a thread each), interrupted at each of its
 * changes to the file system in turn (CELADON_TEST_SIGNAL_AT: the Nth hold
 * sends the signal, so it comes while one thread makes or moves a file and
 * the other goes on making its own), by SIGINT, SIGTERM and SIGHUP, into a new folder and
 * into an existing one: whole vessels or none, and no temporary left. */
Test(faults, signals_at_every_change_of_a_batch_reconstruct_leave_whole_vessels_or_none, .timeout = 300)
{
    char a[300], b[300], out[300];
    draw_photo("a.png", SYNTH_VASE, 200, 260);
    draw_photo("b.png", SYNTH_BOWL, 200, 260);
    snprintf(a, sizeof a, "%s/a.png", dir);
    snprintf(b, sizeof b, "%s/b.png", dir);
    snprintf(out, sizeof out, "%s/vessels", dir);
    const char *args[] = {"reconstruct", a, b, "-o", out, NULL};
    static const int sigs[] = {SIGINT, SIGTERM, SIGHUP};
    int n = 1;
    for (;; n++) {
        remove_tree(out);
        if (n % 2 == 0) /* into an existing folder too: published file by file */
            cr_assert_eq(mkdir(out, 0777), 0);
        int sig = sigs[n % 3];
        char at[32];
        snprintf(at, sizeof at, "%d:%d", n, sig);
        setenv("CELADON_TEST_SIGNAL_AT", at, 1);
        int status;
        cr_assert_eq(waitpid(start(args), &status, 0) > 0, 1);
        cr_expect(WIFSIGNALED(status) ? WTERMSIG(status) == sig : WIFEXITED(status) && WEXITSTATUS(status) == 0,
                  "signal %d at change %d gave status %#x", sig, n, status);
        cr_expect_eq(temporaries_under(dir), 0, "after signal %d at change %d", sig, n);
        expect_whole_vessels(out);
        if (!WIFSIGNALED(status))
            break; /* fewer changes than n: the whole batch ran */
    }
    unsetenv("CELADON_TEST_SIGNAL_AT");
    cr_log_info("interrupted at each of %d changes", n - 1);
    /* Each photo makes its folder, writes six files and publishes them. */
    cr_expect_geq(n, 2 * 8 + 1, "only %d changes to the file system", n - 1);
}

/* The promise under the tests above, for each kind of writer (atomic_file_open,
 * as the OBJ, PLY, JSON and glTF writers do; atomic_temp_name, as the image
 * writers do): a signal that comes while outputs are being written waits
 * for the writes to end, then the process ends by the signal with each
 * output whole or absent and no temporary left. The child raises the
 * signal itself with both files open and written to, then finishes the
 * mesh and gives the image up, as a failing writer does. */
Test(faults, a_signal_while_outputs_are_open_waits_for_them_and_leaves_no_temporary)
{
    static const int sigs[] = {SIGINT, SIGTERM, SIGHUP};
    static const char mesh_text[] = "v 0 0 0\nv 1 1 1\n";
    char mesh[300], image[300];
    snprintf(mesh, sizeof mesh, "%s/signalled/out.obj", dir);
    snprintf(image, sizeof image, "%s/signalled/out.exr", dir);
    for (size_t k = 0; k < sizeof sigs / sizeof *sigs; k++) {
        char sub[300];
        snprintf(sub, sizeof sub, "%s/signalled", dir);
        remove_tree(sub);
        cr_assert_eq(mkdir(sub, 0777), 0);
        pid_t pid = fork();
        cr_assert_geq(pid, 0);
        if (pid == 0) {
            temp_files_install();
            atomic_file af;
            char tmp[4200];
            if (atomic_file_open(&af, mesh) != 0 || fputs("v 0 0 0\n", af.fp) < 0 || fflush(af.fp) != 0)
                _exit(3);
            atomic_temp_name(image, tmp, sizeof tmp);
            FILE *f = fopen(tmp, "wb");
            if (!f || fputs("half an image", f) < 0 || fflush(f) != 0)
                _exit(4);
            if (access(af.temp_path, F_OK) != 0 || access(tmp, F_OK) != 0)
                _exit(5); /* the temporaries exist when the signal comes */
            raise(sigs[k]);
            if (fputs("v 1 1 1\n", af.fp) < 0 || atomic_file_commit(&af) != 0)
                _exit(6);
            fclose(f);
            remove(tmp);
            atomic_temp_done(tmp); /* the last hold ends: the signal acts */
            _exit(7);
        }
        int status;
        cr_assert_eq(waitpid(pid, &status, 0), pid);
        cr_expect(WIFSIGNALED(status) && WTERMSIG(status) == sigs[k], "signal %d gave status %#x", sigs[k], status);
        cr_expect_eq(temporaries_under(sub), 0, "after signal %d", sigs[k]);
        cr_expect(access(image, F_OK) != 0, "the image given up was published");
        char text[64] = "";
        FILE *m = fopen(mesh, "r");
        cr_assert_not_null(m, "the mesh written whole was not published");
        size_t got = fread(text, 1, sizeof text - 1, m);
        fclose(m);
        cr_expect(got == strlen(mesh_text) && !strcmp(text, mesh_text), "the mesh is not whole: '%s'", text);
    }
}

static void *sleep_forever(void *arg)
{
    (void)arg;
    for (;;)
        pause();
    return NULL;
}

/* A writer that never ends its hold (a hung disk) delays a signal by 2 s at
 * most: then the handler, in the other thread, removes the tracked
 * temporary anyway and ends the process. */
Test(faults, a_hold_that_never_ends_delays_a_signal_two_seconds_at_most)
{
    char image[320], sub[300];
    snprintf(sub, sizeof sub, "%s/hung", dir);
    snprintf(image, sizeof image, "%s/out.png", sub);
    cr_assert_eq(mkdir(sub, 0777), 0);
    double t0 = now();
    pid_t pid = fork();
    cr_assert_geq(pid, 0);
    if (pid == 0) {
        temp_files_install();
        pthread_t other; /* made before the hold: it takes the signal */
        if (pthread_create(&other, NULL, sleep_forever, NULL) != 0)
            _exit(3);
        char tmp[4200];
        atomic_temp_name(image, tmp, sizeof tmp);
        FILE *f = fopen(tmp, "wb");
        if (!f || fputs("half an image", f) < 0 || fflush(f) != 0)
            _exit(4);
        kill(getpid(), SIGHUP);
        sleep_forever(NULL);
    }
    int status;
    cr_assert_eq(waitpid(pid, &status, 0), pid);
    double t = now() - t0;
    cr_expect(WIFSIGNALED(status) && WTERMSIG(status) == SIGHUP, "status %#x", status);
    cr_expect_eq(temporaries_under(sub), 0, "the hung writer's temporary was left");
    cr_expect(t >= 1.9 && t < 30.0, "the signal took %.2f s, not the 2 s the handler waits", t);
}

/* A signal that another thread handles while this one holds: the hold
 * ends, and the thread must not go on to end the process normally while
 * the handler cleans up (the batch test once saw exit status 0 for the
 * signal sent at its last change). The child's hold lasts 50 ms (a
 * write), long enough for the other thread to take the signal; then it
 * ends the hold and exits at once, as a batch does after its last rename. */
Test(faults, a_signal_handled_in_another_thread_ends_the_process_after_the_hold)
{
    static const int sigs[] = {SIGINT, SIGTERM, SIGHUP};
    for (size_t k = 0; k < sizeof sigs / sizeof *sigs; k++) {
        pid_t pid = fork();
        cr_assert_geq(pid, 0);
        if (pid == 0) {
            char at[32];
            snprintf(at, sizeof at, "1:%d", sigs[k]);
            setenv("CELADON_TEST_SIGNAL_AT", at, 1);
            temp_files_install();
            pthread_t other; /* not in a hold: the signal goes to it */
            if (pthread_create(&other, NULL, sleep_forever, NULL) != 0)
                _exit(3);
            temp_files_hold();
            nanosleep(&(struct timespec){0, 50000000}, NULL);
            temp_files_release();
            _exit(0);
        }
        int status;
        cr_assert_eq(waitpid(pid, &status, 0), pid);
        cr_expect(WIFSIGNALED(status) && WTERMSIG(status) == sigs[k], "signal %d gave status %#x", sigs[k], status);
    }
}

/* A tmpfs of 16 KiB at dir/full; 0, or -1 when this process may not mount. */
static int mount_small_disk(char *mnt, size_t len)
{
    snprintf(mnt, len, "%s/full", dir);
    cr_assert_eq(mkdir(mnt, 0777), 0);
    return mount("tmpfs", mnt, "tmpfs", 0, "size=16k");
}

static int is_empty(const char *path)
{
    DIR *d = opendir(path);
    cr_assert_not_null(d);
    int n = 0;
    for (struct dirent *e; (e = readdir(d));)
        n += strcmp(e->d_name, ".") && strcmp(e->d_name, "..");
    closedir(d);
    return n == 0;
}

Test(faults, a_full_disk_leaves_nothing_half_written, .timeout = 300)
{
    char mnt[300];
    if (mount_small_disk(mnt, sizeof mnt) != 0)
        cr_skip_test("cannot mount a tmpfs here (needs root): the disk-full case is not tested");
    char scene[300], out[400], photo[300];
    write_scene(scene, sizeof scene);
    draw_photo("a.png", SYNTH_VASE, 400, 520);
    snprintf(photo, sizeof photo, "%s/a.png", dir);

    /* An EXR of 1024 x 1024 floats cannot fit: even this noise-free furnace
     * sphere (every sample of a pixel gives the same value) compresses to
     * about 100 KiB. */
    snprintf(out, sizeof out, "%s/out.exr", mnt);
    cli_result r = cli_run(dir, (const char *[]){"render", scene, "-o", out, "--res", "1024x1024", "--spp", "1", NULL});
    cr_expect_eq(r.status, 1, "render onto a full disk exited %d: %s", r.status, r.err);
    cr_expect_not_null(strstr(r.err, "No space left on device"), "%s", r.err);
    cr_expect(is_empty(mnt), "render left files on the full disk");
    cli_result_free(&r);

    snprintf(out, sizeof out, "%s/vessel", mnt);
    r = cli_run(dir, (const char *[]){"reconstruct", photo, "-o", out, NULL});
    cr_expect_eq(r.status, 1, "reconstruct onto a full disk exited %d: %s", r.status, r.err);
    cr_expect(is_empty(mnt), "reconstruct left files on the full disk");
    cli_result_free(&r);
    umount(mnt);
}
