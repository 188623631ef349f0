/* celadon render -a DIR (Mitsuba's extra search folders): a file the scene
 * names is found in an -a folder when it is nowhere the scene looks itself,
 * the scene's own folders come first, and a folder that does not exist is
 * refused in one line. */
#include <sys/stat.h>

#include "support/cli_run.h"
#include "support/vol_file.h"
#include "test_render_util.h"

/* A scene of an SDF grid read from grids/g.vol. */
static const char *scene_xml =
    "<scene version=\"3.0.0\">\n"
    "  <sensor type=\"perspective\"><transform name=\"to_world\"><lookat origin=\"0.5, 0.5, 4\" "
    "target=\"0.5, 0.5, 0\" up=\"0, 1, 0\"/></transform></sensor>\n"
    "  <shape type=\"sdfgrid\"><string name=\"filename\" value=\"grids/g.vol\"/></shape>\n"
    "  <emitter type=\"constant\"/>\n"
    "</scene>\n";

/* celadon render scene.xml with args before it; exit status, stderr in err. */
static int render_with(render_fixture *f, const char *scene, const char *a1, const char *a2, const char *a3,
                       char *err, size_t errlen)
{
    char out[300];
    snprintf(out, sizeof out, "%s/out.png", f->dir);
    const char *args[] = {"render", scene, "-o", out, "--res", "8x6", "--spp", "1", a1, a2, a3, NULL};
    cli_result r = cli_run(f->dir, args);
    snprintf(err, errlen, "%s", r.err);
    int status = r.status;
    cli_result_free(&r);
    return status;
}

static void make_dir(const render_fixture *f, const char *name)
{
    char path[300];
    snprintf(path, sizeof path, "%s/%s", f->dir, name);
    cr_assert_eq(mkdir(path, 0755), 0, "mkdir %s", path);
}

Test(render_search_dirs, an_a_folder_is_searched_after_the_scenes_own)
{
    render_fixture f;
    render_fixture_open(&f);
    char scene[300], data[300], empty[300], both[700], path[300], err[4096];
    make_dir(&f, "scenes");
    make_dir(&f, "data");
    make_dir(&f, "data/grids");
    make_dir(&f, "empty");
    render_write_file(&f, "scenes/scene.xml", scene_xml, scene, sizeof scene);
    const float plane[8] = {-1, -1, -1, -1, 1, 1, 1, 1}; /* the plane z = 1/2 */
    snprintf(path, sizeof path, "%s/data/grids/g.vol", f.dir);
    vol_file_write(path, 2, 2, 2, 1, plane);
    snprintf(data, sizeof data, "%s/data", f.dir);
    snprintf(empty, sizeof empty, "%s/empty", f.dir);
    snprintf(both, sizeof both, "%s;%s", empty, data);

    /* not found where the scene looks */
    int status = render_with(&f, scene, NULL, NULL, NULL, err, sizeof err);
    cr_expect(status == 2 && strstr(err, "file 'grids/g.vol' not found"), "%d: %s", status, err);
    /* found in the -a folder, as -a, --append and in a ';' list */
    const char *forms[3][2] = {{"-a", data}, {"--append", data}, {"-a", both}};
    for (int k = 0; k < 3; k++) {
        status = render_with(&f, scene, forms[k][0], forms[k][1], NULL, err, sizeof err);
        cr_expect_eq(status, 0, "%s %s: %d: %s", forms[k][0], forms[k][1], status, err);
    }
    /* a file beside the scene comes first: the -a folder's is not read (the
     * one beside the scene is no grid, so the render says which was read) */
    make_dir(&f, "scenes/grids");
    render_write_file(&f, "scenes/grids/g.vol", "not a grid", path, sizeof path);
    status = render_with(&f, scene, "-a", data, NULL, err, sizeof err);
    cr_expect(status == 2 && cli_count_lines(err) == 1 && strstr(err, "scenes/grids/g.vol: not a Mitsuba .vol file"),
              "%d: %s", status, err);
    /* a folder that is not there, and an empty name */
    status = render_with(&f, scene, "-a", "/nonexistent/folder", NULL, err, sizeof err);
    cr_expect(status == 2 && cli_count_lines(err) == 1 && strstr(err, "-a /nonexistent/folder: no such folder"),
              "%d: %s", status, err);
    status = render_with(&f, scene, "-a", "", NULL, err, sizeof err);
    cr_expect(status == 2 && cli_count_lines(err) == 1, "%d: %s", status, err);
    render_fixture_close(&f);
}
