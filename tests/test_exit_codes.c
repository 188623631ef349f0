/* The exit codes (docs/faults.md): every command run into a folder it
 * cannot write exits 1 with one line naming the path, before the work
 * (issue 15: mesh said 2, reconstruct 2, render 1 only after the whole
 * render); a film size the help allows but memory does not is bad input
 * (2, not 1). */
#include <criterion/criterion.h>
#include <stdio.h>
#include <string.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <unistd.h>

#include "support/cli_run.h"
#include "support/synth_vessel.h"
#include "test_render_util.h"

static render_fixture fx;
static char locked[128]; /* the folder no command may write */
static int mounted;

/* A read-only tmpfs when running as root (who writes anywhere else),
 * a folder without write permission otherwise. */
static void open_fixture(void)
{
    render_fixture_open(&fx);
    snprintf(locked, sizeof locked, "%s/locked", fx.dir);
    cr_assert_eq(mkdir(locked, 0777), 0);
    if (geteuid() != 0)
        cr_assert_eq(chmod(locked, 0555), 0);
    else if (mount("tmpfs", locked, "tmpfs", MS_RDONLY, "size=16k") == 0)
        mounted = 1;
}

static void close_fixture(void)
{
    if (mounted)
        umount(locked);
    chmod(locked, 0777);
    render_fixture_close(&fx);
}

TestSuite(exit_codes, .init = open_fixture, .fini = close_fixture);

static void skip_unless_locked(void)
{
    if (geteuid() == 0 && !mounted)
        cr_skip_test("running as root where no read-only tmpfs can be mounted: no folder is unwritable");
}

/* Runs celadon ARGS; expects exit code `code` within seconds and one
 * line on stderr that holds needle. */
static void expect_exit(const char *const *args, int code, const char *needle, double seconds)
{
    cli_result r = cli_run_within(fx.dir, args, seconds);
    cr_expect_eq(r.status, code, "celadon %s exited %d, not %d; stderr: %s", args[0], r.status, code, r.err);
    cr_expect_eq(cli_count_lines(r.err), 1, "celadon %s: %s", args[0], r.err);
    cr_expect_not_null(strstr(r.err, needle), "celadon %s: '%s' not in: %s", args[0], needle, r.err);
    cli_result_free(&r);
}

static const char sphere_xml[] =
    "<scene version=\"3.0.0\"><sensor type=\"perspective\"><transform name=\"to_world\">"
    "<lookat origin=\"0,0,4\" target=\"0,0,0\" up=\"0,1,0\"/></transform></sensor>"
    "<emitter type=\"constant\"/><shape type=\"sphere\"/></scene>\n";

static void draw_photo(char *path, size_t len)
{
    synth_params p = synth_defaults(SYNTH_VASE, 200, 260);
    p.subrows = 2;
    image_t img;
    cr_assert_eq(synth_draw(&p, &img), 0);
    char err[256];
    snprintf(path, len, "%s/photo.png", fx.dir);
    cr_assert_eq(synth_write(path, &img, 8, err, sizeof err), 0, "%s", err);
    image_free(&img);
}

/* Every command, with good inputs, into the locked folder: 1, named, in a
 * few seconds (a render of 4096 x 4096 at 64 spp would take minutes). */
Test(exit_codes, every_command_into_an_unwritable_folder_exits_1_before_working, .timeout = 240)
{
    skip_unless_locked();
    char scene[256], profile[256], photo[256], out[256], part1[256], part2[256];
    render_write_file(&fx, "scene.xml", sphere_xml, scene, sizeof scene);
    render_write_profile(&fx, "profile.json", "plum");
    snprintf(profile, sizeof profile, "%s/profile.json", fx.dir);
    draw_photo(photo, sizeof photo);
    snprintf(part1, sizeof part1, "%s/part1.exr", fx.dir);
    snprintf(part2, sizeof part2, "%s/part2.exr", fx.dir);
    for (int k = 0; k < 2; k++) {
        cli_result r = cli_run(fx.dir, (const char *[]){"render", scene, "-o", k ? part2 : part1, "--part",
                                                         k ? "2/2" : "1/2", "--res", "8x8", "--spp", "2", NULL});
        cr_assert_eq(r.status, 0, "%s", r.err);
        cli_result_free(&r);
    }

    snprintf(out, sizeof out, "%s/image.png", locked);
    expect_exit((const char *[]){"render", scene, "-o", out, "--res", "4096x4096", "--spp", "64", NULL}, 1, out, 60);
    snprintf(out, sizeof out, "%s/vessel.obj", locked);
    expect_exit((const char *[]){"mesh", profile, "-o", out, NULL}, 1, out, 60);
    snprintf(out, sizeof out, "%s/vessel", locked);
    expect_exit((const char *[]){"reconstruct", photo, "-o", out, NULL}, 1, out, 60);
    snprintf(out, sizeof out, "%s/merged.exr", locked);
    expect_exit((const char *[]){"merge", part1, part2, "-o", out, NULL}, 1, out, 60);
    snprintf(out, sizeof out, "%s/museum", locked);
    expect_exit((const char *[]){"museum", photo, "-o", out, NULL}, 1, out, 60);
    snprintf(out, sizeof out, "%s/check", locked);
    expect_exit((const char *[]){"crosscheck", scene, "--segments", "8,16", "-o", out, "--res", "1024x1024",
                                 "--spp", "64", NULL},
                1, out, 60);
}

Test(exit_codes, a_film_too_large_for_memory_is_bad_input)
{
    char scene[256], out[256];
    render_write_file(&fx, "scene.xml", sphere_xml, scene, sizeof scene);
    snprintf(out, sizeof out, "%s/image.png", fx.dir);
    expect_exit((const char *[]){"render", scene, "-o", out, "--res", "65536x65536", NULL}, 2, "out of range", 60);
    cr_expect_neq(access(out, F_OK), 0);
}
