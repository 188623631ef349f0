/* celadon render end to end, and determinism of the render loop. */
#include <fcntl.h>
#include <openexr.h>
#include <spawn.h>
#include <signal.h>
#include <sys/wait.h>

#include "celadon/image.h"
#include "support/cli_run.h"
#include "test_render_util.h"

extern char **environ;

static const char *tiny_xml =
    "<scene version=\"3.0.0\">\n"
    "  <default name=\"spp\" value=\"4\"/>\n"
    "  <sensor type=\"perspective\">\n"
    "    <transform name=\"to_world\"><lookat origin=\"0, 0.5, 3\" target=\"0, 0.5, 0\" up=\"0, 1, 0\"/></transform>\n"
    "    <sampler type=\"independent\"><integer name=\"sample_count\" value=\"$spp\"/></sampler>\n"
    "    <film type=\"hdrfilm\"><integer name=\"width\" value=\"24\"/><integer name=\"height\" value=\"16\"/></film>\n"
    "  </sensor>\n"
    "  <shape type=\"sor\"><string name=\"filename\" value=\"profile.json\"/>\n"
    "    <bsdf type=\"plastic\"><rgb name=\"diffuse_reflectance\" value=\"0.2, 0.5, 0.3\"/></bsdf></shape>\n"
    "  <shape type=\"rectangle\"><transform name=\"to_world\"><rotate x=\"1\" angle=\"-90\"/><scale value=\"3\"/></transform></shape>\n"
    "  <shape type=\"disk\"><transform name=\"to_world\"><rotate x=\"1\" angle=\"90\"/><translate y=\"3\"/></transform>\n"
    "    <emitter type=\"area\"><rgb name=\"radiance\" value=\"5\"/></emitter></shape>\n"
    "  <emitter type=\"point\"><point name=\"position\" value=\"1, 2, 1\"/><rgb name=\"intensity\" value=\"2\"/></emitter>\n"
    "</scene>\n";

/* Runs celadon with args (NULL-terminated); stderr into err. Exit code. */
static int run(const render_fixture *f, const char *const *args, char *err, size_t errlen)
{
    cli_result r = cli_run(f->dir, args);
    snprintf(err, errlen, "%s", r.err);
    cli_result_free(&r);
    return r.status;
}

Test(render_cli, exr_with_aovs_and_png)
{
    render_fixture f;
    char scene[256], exr[256], png[256], err[4096];
    render_fixture_with_scene(&f, "plum", tiny_xml, scene, sizeof scene);
    snprintf(exr, sizeof exr, "%s/out.exr", f.dir);
    snprintf(png, sizeof png, "%s/out.png", f.dir);
    const char *a1[] = {"render", scene, "-o", exr, "--threads", "2", "--aov", "depth,normal,albedo", "-D", "spp=2",
                        NULL};
    cr_assert_eq(run(&f, a1, err, sizeof err), 0, "%s", err);
    int w, h, c;
    char why[256];
    cr_assert_eq(image_probe(exr, &w, &h, &c, why, sizeof why), 0, "%s", why);
    cr_expect(w == 24 && h == 16 && c == 3 + 1 + 3 + 3, "%dx%d with %d channels", w, h, c);
    /* the channels as Blender's compositor and Nuke read them (EXR lists them sorted) */
    exr_context_t ctx;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    cr_assert_eq(exr_start_read(&ctx, exr, &init), EXR_ERR_SUCCESS);
    const exr_attr_chlist_t *chl;
    cr_assert_eq(exr_get_channels(ctx, 0, &chl), EXR_ERR_SUCCESS);
    char names[256] = "";
    for (int i = 0; i < chl->num_channels; i++)
        snprintf(names + strlen(names), sizeof names - strlen(names), "%s ", chl->entries[i].name.str);
    exr_finish(&ctx);
    cr_expect_str_eq(names, "B G N.X N.Y N.Z R Z albedo.B albedo.G albedo.R ");
    const char *a2[] = {"render", scene, "-o", png, "--res", "20x10", "--spp", "2", "--geometry", "mesh:64", NULL};
    cr_assert_eq(run(&f, a2, err, sizeof err), 0, "%s", err);
    cr_assert_eq(image_probe(png, &w, &h, &c, why, sizeof why), 0, "%s", why);
    cr_expect(w == 20 && h == 10 && c == 3, "%dx%d with %d channels", w, h, c);
    render_fixture_close(&f);
}

/* Each bad input: exit 2, one line naming the problem, no output file. */
static void expect_refused(const render_fixture *f, const char *xml, const char *const *extra, const char *needle)
{
    char scene[256], out[256], err[4096];
    render_write_file(f, "bad.xml", xml, scene, sizeof scene);
    snprintf(out, sizeof out, "%s/bad.exr", f->dir);
    const char *args[16] = {"render", scene, "-o", out};
    int n = 4;
    for (; extra && *extra; extra++)
        args[n++] = *extra;
    args[n] = NULL;
    cr_expect_eq(run(f, args, err, sizeof err), 2, "stderr: %s", err);
    cr_expect_eq(cli_count_lines(err), 1, "stderr: %s", err);
    cr_expect_not_null(strstr(err, needle), "'%s' not in: %s", needle, err);
    cr_expect_neq(access(out, F_OK), 0, "an output file was written");
}

Test(render_cli, bad_input_exits_2_with_one_line_and_no_file)
{
    render_fixture f;
    render_fixture_open(&f);
    render_write_profile(&f, "profile.json", "plum");
    render_write_file(&f, "notjson.json", "{ nope", (char[256]){0}, 256);
    render_write_file(&f, "broken.obj", "v 0 0 0\nv 1 0 0\nf 1 2 7\n", (char[256]){0}, 256);
    /* A scene line that the parser accepts but the renderer must refuse. */
    expect_refused(&f,
                   "<scene version=\"3.0.0\">\n<sensor type=\"perspective\"/>\n<shape type=\"sor\">\n"
                   "<string name=\"filename\" value=\"notjson.json\"/></shape></scene>",
                   NULL, "bad.xml:3:");
    expect_refused(&f,
                   "<scene version=\"3.0.0\">\n<sensor type=\"perspective\"/>\n\n<shape type=\"obj\">\n"
                   "<string name=\"filename\" value=\"broken.obj\"/></shape></scene>",
                   NULL, "bad.xml:4:");
    expect_refused(&f, "<scene version=\"3.0.0\">\n<shape type=\"sphere\"/></scene>", NULL, "bad.xml:1:");
    expect_refused(&f, "<scene version=\"3.0.0\"><bsdf type=\"blend\"/></scene>", NULL, "bad.xml:1:");
    expect_refused(&f, tiny_xml, (const char *[]){"--geometry", "mesh:2", NULL}, "--geometry");
    /* The rings follow N: a million segments would need billions of triangles. */
    expect_refused(&f, tiny_xml, (const char *[]){"--geometry", "mesh:1000000", NULL}, "use fewer segments");
    expect_refused(&f, tiny_xml, (const char *[]){"--res", "10by10", NULL}, "--res");
    expect_refused(&f, tiny_xml, (const char *[]){"--sampler", "sobol", NULL}, "--sampler");
    /* 2^24 - 1 samples round up past the limit 2^24 to a prime's square. */
    expect_refused(&f, tiny_xml, (const char *[]){"--sampler", "orthogonal", "--spp", "16777215", NULL},
                   "rounds up to");
    render_fixture_close(&f);
}

/* Every sampler: the same seed gives the same bits on 1 and 2 threads,
 * another seed another image. */
Test(render_determinism, same_seed_same_image_any_thread_count)
{
    render_fixture f;
    char scene[256];
    render_fixture_with_scene(&f, "plum", tiny_xml, scene, sizeof scene);
    const char *samplers[] = {"independent", "stratified", "multijitter", "orthogonal", "ldsampler", "zsobol"};
    for (int i = 0; i < 6; i++) {
        scene_options bo = scene_options_default();
        bo.sampler = samplers[i];
        bo.seed = 5;
        int w, h, nch;
        float *a = render_to_pixels_with(scene, &bo, 1, 0, &w, &h, &nch);
        float *b = render_to_pixels_with(scene, &bo, 2, 0, &w, &h, &nch);
        bo.seed = 6;
        float *c = render_to_pixels_with(scene, &bo, 2, 0, &w, &h, &nch);
        size_t n = (size_t)w * h * nch;
        cr_expect_eq(memcmp(a, b, n * sizeof *a), 0, "%s: seed 5 on 1 and 2 threads differ", samplers[i]);
        cr_expect_neq(memcmp(a, c, n * sizeof *a), 0, "%s: seeds 5 and 6 give the same image", samplers[i]);
        free(a), free(b), free(c);
    }
    render_fixture_close(&f);
}

/* Ctrl-C: the render stops, the partial image is written whole, exit 130. */
Test(render_cli, sigint_writes_the_partial_image)
{
    render_fixture f;
    char scene[256], out[256], errpath[256];
    render_fixture_with_scene(&f, "plum", tiny_xml, scene, sizeof scene);
    snprintf(out, sizeof out, "%s/partial.exr", f.dir);
    snprintf(errpath, sizeof errpath, "%s/stderr.txt", f.dir);
    char *argv[] = {(char *)cli_bin(), "render", scene, "-o", out, "--spp", "10000000", "--threads", "2", NULL};
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 2, errpath, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    pid_t pid;
    cr_assert_eq(posix_spawn(&pid, argv[0], &fa, NULL, argv, environ), 0);
    posix_spawn_file_actions_destroy(&fa);
    /* Once it catches SIGINT (it may take seconds to start on a busy machine),
     * let it render a moment. */
    cr_assert(cli_wait_for_handler(pid, SIGINT, 60), "celadon never caught SIGINT");
    usleep(500000);
    kill(pid, SIGINT);
    int status;
    cr_assert_eq(waitpid(pid, &status, 0), pid);
    cr_assert(WIFEXITED(status), "celadon died from signal %d", WIFSIGNALED(status) ? WTERMSIG(status) : -1);
    cr_expect_eq(WEXITSTATUS(status), 130);
    int w, h, c;
    char why[256];
    cr_expect_eq(image_probe(out, &w, &h, &c, why, sizeof why), 0, "no partial image: %s", why);
    render_fixture_close(&f);
}
