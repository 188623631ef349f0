/* Parts of a render (parts.h) and `celadon merge`; the scene digest that
 * tells parts of different renders apart; `celadon render --frames`. The
 * truth is the one-process render of the same seed. */
#include <criterion/criterion.h>

#include <jansson.h>
#include <openexr.h>

#include "celadon/parts.h"
#include "test_distribute_support.h"

/* The shares of every split tile the samples: consecutive, disjoint, each
 * within one sample of spp / n. */
Test(parts, shares_tile_the_samples)
{
    static const int spps[] = {1, 2, 7, 64, 1000, 16777216};
    for (size_t i = 0; i < sizeof spps / sizeof spps[0]; i++)
        for (int n = 1; n <= 40; n += 3) {
            int spp = spps[i], next = 0;
            for (int k = 1; k <= n; k++) {
                int s0, s1;
                int rc = render_part_samples((render_part){k, n}, spp, &s0, &s1);
                cr_assert_eq(s0, next, "spp %d, part %d/%d starts at %d, not %d", spp, k, n, s0, next);
                cr_assert(rc == 0 ? s1 > s0 : s1 == s0);
                cr_assert(s1 - s0 >= spp / n && s1 - s0 <= spp / n + 1);
                next = s1;
            }
            cr_assert_eq(next, spp);
        }
}

Test(parts, parse)
{
    render_part p;
    cr_assert_eq(render_part_parse("3/8", &p), 0);
    cr_assert(p.k == 3 && p.n == 8);
    const char *bad[] = {"0/4", "5/4", "3", "3/", "/4", "-1/4", "3/4x", " 3/4", "1/1000001", "a/b"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
        cr_expect_neq(render_part_parse(bad[i], &p), 0, "'%s' accepted", bad[i]);
}

/* Renders part k of n of the orbit scene to dir/name; extra args appended. */
static void render_part_file(const render_fixture *f, const char *scene, int k, int n, const char *name,
                             const char *const *extra)
{
    char out[256], part[32], err[4096];
    snprintf(part, sizeof part, "%d/%d", k, n);
    const char *args[24] = {"render", scene, "-o", fixture_path(f, name, out, sizeof out), "--part", part,
                            "--threads", "1"};
    int a = 8;
    for (; extra && *extra; extra++)
        args[a++] = *extra;
    args[a] = NULL;
    cr_assert_eq(run_celadon(f, args, err, sizeof err), 0, "%s", err);
}

/* The one-process render into single.exr and its n parts into part1.exr ...
 * (paths into p), all with the extra options. */
static void render_single_and_parts(const render_fixture *f, const char *scene, int n, const char *const *extra,
                                    char *single, size_t single_len, char (*p)[256])
{
    char err[4096];
    const char *args[24] = {"render", scene, "-o", fixture_path(f, "single.exr", single, single_len), "--threads",
                            "2"};
    int a = 6;
    for (const char *const *e = extra; *e; e++)
        args[a++] = *e;
    args[a] = NULL;
    cr_assert_eq(run_celadon(f, args, err, sizeof err), 0, "%s", err);
    for (int k = 1; k <= n; k++) {
        char name[32];
        snprintf(name, sizeof name, "part%d.exr", k);
        render_part_file(f, scene, k, n, name, extra);
        fixture_path(f, name, p[k - 1], sizeof p[k - 1]);
    }
}

/* Four parts merged, in any order, give the one-process render. */
Test(parts, four_parts_merged_are_the_single_render, .timeout = 300)
{
    render_fixture f;
    char scene[256], single[256], merged[256], shuffled[256], p[4][256], err[4096];
    render_fixture_with_scene(&f, "plum", orbit_xml, scene, sizeof scene);
    render_single_and_parts(&f, scene, 4, (const char *[]){"--aov", "depth", NULL}, single, sizeof single, p);
    const char *m1[] = {"merge", p[0], p[1], p[2], p[3], "-o", fixture_path(&f, "merged.exr", merged, sizeof merged),
                        NULL};
    cr_assert_eq(run_celadon(&f, m1, err, sizeof err), 0, "%s", err);
    const char *m2[] = {"merge", p[2], p[0], p[3], p[1], "-o",
                        fixture_path(&f, "shuffled.exr", shuffled, sizeof shuffled), NULL};
    cr_assert_eq(run_celadon(&f, m2, err, sizeof err), 0, "%s", err);
    image_t s = read_image(single), m = read_image(merged), sh = read_image(shuffled);
    cr_assert_eq(s.channels, 4, "RGB and depth: %d channels", s.channels);
    double worst;
    cr_expect(same_within_rounding(&s, &m, &worst), "merged parts differ from the single render by %g", worst);
    cr_expect_eq(memcmp(m.data, sh.data, sizeof(float) * (size_t)m.width * m.height * m.channels), 0,
                 "the merge depends on the order of its arguments");
    /* And the parts are images of their own, each noisier than the whole. */
    image_t p1 = read_image(p[0]);
    cr_expect(!same_within_rounding(&s, &p1, &worst));
    image_free(&s), image_free(&m), image_free(&sh), image_free(&p1);
    render_fixture_close(&f);
}

/* The orbit with an XYZ + alpha film, a tent filter wider than a pixel and
 * sample_border, at a height that is no multiple of the tiles. */
static const char *const xyza_xml =
    "<scene version=\"3.0.0\">\n"
    "  <sensor type=\"perspective\">\n"
    "    <transform name=\"to_world\"><lookat origin=\"0, 0.8, 3\" target=\"0, 0.4, 0\" up=\"0, 1, 0\"/></transform>\n"
    "    <sampler type=\"independent\"><integer name=\"sample_count\" value=\"12\"/></sampler>\n"
    "    <film type=\"hdrfilm\"><integer name=\"width\" value=\"40\"/><integer name=\"height\" value=\"27\"/>\n"
    "      <string name=\"pixel_format\" value=\"xyza\"/><boolean name=\"sample_border\" value=\"true\"/>\n"
    "      <rfilter type=\"tent\"><float name=\"radius\" value=\"1.5\"/></rfilter></film>\n"
    "  </sensor>\n"
    "  <shape type=\"sor\"><string name=\"filename\" value=\"profile.json\"/>\n"
    "    <bsdf type=\"plastic\"><rgb name=\"diffuse_reflectance\" value=\"0.2, 0.5, 0.3\"/></bsdf></shape>\n"
    "  <emitter type=\"point\"><point name=\"position\" x=\"1\" y=\"2\" z=\"2\"/><rgb name=\"intensity\" value=\"5\"/></emitter>\n"
    "</scene>\n";

/* The header attributes film_write records, as one string. */
static void header_summary(const char *path, char *out, size_t outlen)
{
    exr_context_t ctx;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    cr_assert_eq(exr_start_read(&ctx, path, &init), EXR_ERR_SUCCESS, "%s", path);
    int32_t spp = 0, len = 0;
    const char *seed = "", *integrator = "", *camera = "";
    exr_attr_m44f_t m;
    cr_assert_eq(exr_attr_get_int(ctx, 0, "spp", &spp), EXR_ERR_SUCCESS, "%s: no spp", path);
    cr_assert_eq(exr_attr_get_string(ctx, 0, "seed", &len, &seed), EXR_ERR_SUCCESS);
    cr_assert_eq(exr_attr_get_string(ctx, 0, "integrator", &len, &integrator), EXR_ERR_SUCCESS);
    cr_assert_eq(exr_attr_get_string(ctx, 0, "camera", &len, &camera), EXR_ERR_SUCCESS);
    cr_assert_eq(exr_attr_get_m44f(ctx, 0, "worldToCamera", &m), EXR_ERR_SUCCESS);
    int n = snprintf(out, outlen, "spp %d seed %s integrator %s camera %s w2c", spp, seed, integrator, camera);
    for (int i = 0; i < 16 && n > 0 && (size_t)n < outlen; i++)
        n += snprintf(out + n, outlen - (size_t)n, " %.6g", m.m[i]);
    exr_finish(&ctx);
}

/* Merged parts keep the film's pixel format (its A is summed with the colour,
 * X, Y, Z converted once at the end), its splatting filter across the bands
 * and the border, and the render's metadata: the file one process writes. */
Test(parts, merged_parts_keep_the_pixel_format_filter_and_metadata, .timeout = 300)
{
    render_fixture f;
    char scene[256], single[256], merged[256], p[3][256], err[4096];
    render_fixture_with_scene(&f, "plum", xyza_xml, scene, sizeof scene);
    render_single_and_parts(&f, scene, 3, (const char *[]){NULL}, single, sizeof single, p);
    const char *m1[] = {"merge", p[2], p[0], p[1], "-o", fixture_path(&f, "merged.exr", merged, sizeof merged),
                        NULL};
    cr_assert_eq(run_celadon(&f, m1, err, sizeof err), 0, "%s", err);
    image_t s = read_image(single), m = read_image(merged);
    cr_assert_eq(s.channels, 4, "X, Y, Z, A: %d channels", s.channels);
    double worst;
    cr_expect(same_within_rounding(&s, &m, &worst), "merged parts differ from the single render by %g", worst);
    char hs[1024], hm[1024];
    header_summary(single, hs, sizeof hs);
    header_summary(merged, hm, sizeof hm);
    cr_expect_str_eq(hm, hs);
    cr_expect_not_null(strstr(hs, "spp 12 "), "%s", hs);
    image_free(&s), image_free(&m);
    render_fixture_close(&f);
}

/* A sampler whose numbers depend on the sample's index (zsobol: Owen-scrambled
 * Sobol points across the pixel's samples) gives the same image in parts:
 * each part takes its samples by their global index. */
Test(parts, parts_of_a_zsobol_render_merge_to_the_single_render, .timeout = 300)
{
    render_fixture f;
    char scene[256], single[256], merged[256], p[3][256], err[4096];
    render_fixture_with_scene(&f, "plum", orbit_xml, scene, sizeof scene);
    render_single_and_parts(&f, scene, 3, (const char *[]){"--sampler", "zsobol", NULL}, single, sizeof single, p);
    const char *m[] = {"merge", p[0], p[1], p[2], "-o", fixture_path(&f, "merged.exr", merged, sizeof merged), NULL};
    cr_assert_eq(run_celadon(&f, m, err, sizeof err), 0, "%s", err);
    image_t a = read_image(single), b = read_image(merged);
    double worst;
    cr_expect(same_within_rounding(&a, &b, &worst), "merged zsobol parts differ from the single render by %g", worst);
    image_free(&a), image_free(&b);
    render_fixture_close(&f);
}

/* A set that is not all parts of one render: exit 2, one line naming the
 * problem, no output. */
static void expect_refused(const render_fixture *f, const char *const *parts, const char *needle)
{
    char out[256], err[4096];
    const char *args[16] = {"merge"};
    int n = 1;
    for (; *parts; parts++)
        args[n++] = *parts;
    args[n++] = "-o";
    args[n++] = fixture_path(f, "refused.png", out, sizeof out);
    args[n] = NULL;
    cr_expect_eq(run_celadon(f, args, err, sizeof err), 2, "stderr: %s", err);
    cr_expect_eq(cli_count_lines(err), 1, "stderr: %s", err);
    cr_expect_not_null(strstr(err, needle), "'%s' not in: %s", needle, err);
    cr_expect_neq(access(out, F_OK), 0, "an output file was written");
}

Test(parts, merge_refuses_missing_duplicated_foreign_and_incomplete_parts, .timeout = 300)
{
    render_fixture f;
    char scene[256], p1[256], p2[256], p3[256], seed[256], res[256], frame[256], other[256], cut[256], img[256];
    render_fixture_with_scene(&f, "plum", orbit_xml, scene, sizeof scene);
    const char *spp[] = {"-D", "spp=12", NULL};
    render_part_file(&f, scene, 1, 3, "p1.exr", spp);
    render_part_file(&f, scene, 2, 3, "p2.exr", spp);
    render_part_file(&f, scene, 3, 3, "p3.exr", spp);
    render_part_file(&f, scene, 2, 3, "seed.exr", (const char *[]){"-D", "spp=12", "--seed", "9", NULL});
    render_part_file(&f, scene, 2, 3, "res.exr", (const char *[]){"-D", "spp=12", "--res", "32x24", NULL});
    render_part_file(&f, scene, 2, 3, "frame.exr", (const char *[]){"-D", "spp=12", "-D", "frame=10", NULL});
    render_part_file(&f, scene, 2, 4, "other.exr", spp);
    fixture_path(&f, "p1.exr", p1, sizeof p1), fixture_path(&f, "p2.exr", p2, sizeof p2);
    fixture_path(&f, "p3.exr", p3, sizeof p3), fixture_path(&f, "seed.exr", seed, sizeof seed);
    fixture_path(&f, "res.exr", res, sizeof res), fixture_path(&f, "frame.exr", frame, sizeof frame);
    fixture_path(&f, "other.exr", other, sizeof other);
    expect_refused(&f, (const char *[]){p1, p3, NULL}, "missing: 2/3");
    expect_refused(&f, (const char *[]){p1, p2, p2, p3, NULL}, "given twice");
    expect_refused(&f, (const char *[]){p1, seed, p3, NULL}, "its seed is 9");
    expect_refused(&f, (const char *[]){p1, frame, p3, NULL}, "scene digest");
    expect_refused(&f, (const char *[]){p1, res, p3, NULL}, "scene digest");
    expect_refused(&f, (const char *[]){p1, other, p3, NULL}, "part of 4");
    /* Not a part at all: an image without the header, a file that is no EXR. */
    char err[4096];
    const char *plain[] = {"render", scene, "-o", fixture_path(&f, "image.exr", img, sizeof img), "-D", "spp=1",
                           NULL};
    cr_assert_eq(run_celadon(&f, plain, err, sizeof err), 0, "%s", err);
    expect_refused(&f, (const char *[]){p1, img, p3, NULL}, "not a part of a celadon render");
    render_write_file(&f, "junk.exr", "not an exr", cut, sizeof cut);
    expect_refused(&f, (const char *[]){p1, p2, cut, NULL}, "junk.exr");
    /* A part cut short: its header reads, its pixels do not (exited 1). */
    char truncated[256];
    size_t len = 0;
    char *bytes = render_read_file(p2, &len);
    cr_assert(bytes && len > 600);
    render_write_bytes(&f, "truncated.exr", bytes, len / 2, truncated, sizeof truncated);
    free(bytes);
    expect_refused(&f, (const char *[]){p1, truncated, p3, NULL}, "truncated.exr");
    /* -o naming one of the parts: refused before anything is written (it
     * overwrote that part). */
    size_t before_len = 0, after_len = 0;
    char *before = render_read_file(p1, &before_len);
    const char *onto[] = {"merge", p1, p2, p3, "-o", p1, NULL};
    cr_expect_eq(run_celadon(&f, onto, err, sizeof err), 2, "stderr: %s", err);
    cr_expect_eq(cli_count_lines(err), 1, "stderr: %s", err);
    cr_expect_not_null(strstr(err, "is one of the parts"), "%s", err);
    char *after = render_read_file(p1, &after_len);
    cr_expect(before && after && before_len == after_len && !memcmp(before, after, before_len), "p1.exr changed");
    free(before), free(after);
    /* A part whose render was interrupted says so in its header. */
    film_t film;
    cr_assert_eq(film_init(&film, 64, 48, NULL, 0, err, sizeof err), 0);
    scene_t *s = scene_create_from_file(scene, (scene_define[]){{"spp", "12", false}}, 1, NULL, err, sizeof err);
    cr_assert_not_null(s, "%s", err);
    fixture_path(&f, "cut.exr", cut, sizeof cut);
    cr_assert_eq(render_part_write(&film, s, (render_part){2, 3}, 0, cut, err, sizeof err), 0, "%s", err);
    expect_refused(&f, (const char *[]){p1, cut, p3, NULL}, "incomplete");
    scene_destroy(s);
    film_free(&film);
    /* More parts than samples. */
    char out[256];
    const char *many[] = {"render", scene, "-o", fixture_path(&f, "many.exr", out, sizeof out), "-D", "spp=2",
                          "--part", "1/3", NULL};
    cr_expect_eq(run_celadon(&f, many, err, sizeof err), 2, "%s", err);
    cr_expect_not_null(strstr(err, "use at most 2 parts"), "%s", err);
    render_fixture_close(&f);
}

/* The digest follows what the scene is built from, not how its XML is
 * laid out. */
Test(parts, scene_digest_follows_the_scene_and_its_files)
{
    render_fixture f;
    char scene[256], spaced[256], err[1024];
    render_fixture_with_scene(&f, "plum", orbit_xml, scene, sizeof scene);
    char *loose = malloc(strlen(orbit_xml) * 2 + 64);
    cr_assert_not_null(loose);
    snprintf(loose, strlen(orbit_xml) * 2 + 64, "<!-- the same scene -->\n%s", orbit_xml);
    for (char *c = strstr(loose, "\n  "); c; c = strstr(c + 1, "\n  "))
        c[1] = '\t'; /* other whitespace */
    render_write_file(&f, "spaced.xml", loose, spaced, sizeof spaced);
    free(loose);
    scene_options o = scene_options_default();
    uint64_t d[8];
    const scene_define frame = {"frame", "5", false};
    scene_options res = o, seed = o, other_sampler = o, own_sampler = o;
    res.width = 32, res.height = 24;
    seed.seed = 77;
    other_sampler.sampler = "zsobol", own_sampler.sampler = "independent"; /* the scene's is independent */
    struct {
        const char *path;
        const scene_define *defs;
        const scene_options *opt;
    } cases[7] = {{scene, NULL, &o},    {spaced, NULL, &o},         {scene, &frame, &o},      {scene, NULL, &res},
                  {scene, NULL, &seed}, {scene, NULL, &other_sampler}, {scene, NULL, &own_sampler}};
    for (int i = 0; i < 7; i++) {
        scene_t *s = scene_create_from_file(cases[i].path, cases[i].defs, cases[i].defs != NULL, cases[i].opt, err,
                                            sizeof err);
        cr_assert_not_null(s, "%s", err);
        d[i] = scene_digest(s);
        scene_destroy(s);
    }
    /* The same XML after the vessel's profile changed. */
    render_write_profile(&f, "profile.json", "cylinder");
    scene_t *s = scene_create_from_file(scene, NULL, 0, &o, err, sizeof err);
    cr_assert_not_null(s, "%s", err);
    d[7] = scene_digest(s);
    scene_destroy(s);
    cr_expect_eq(d[0], d[1], "a comment and other whitespace changed the digest");
    cr_expect_neq(d[0], d[2], "-D frame=5 kept the digest");
    cr_expect_neq(d[0], d[3], "another film size kept the digest");
    cr_expect_eq(d[0], d[4], "the seed, which parts record apart, changed the digest");
    cr_expect_neq(d[0], d[5], "--sampler zsobol kept the digest");
    cr_expect_eq(d[0], d[6], "--sampler naming the scene's own sampler changed the digest");
    cr_expect_neq(d[0], d[7], "another profile.json kept the digest");
    render_fixture_close(&f);
}

/* --frames A:B:S renders each frame with -D frame=F into the name with the
 * # run replaced; a frame is the render of its -D frame. */
Test(parts, frames_render_each_frame, .timeout = 300)
{
    render_fixture f;
    char scene[256], pattern[256], one[256], err[4096], path[256];
    render_fixture_with_scene(&f, "plum", orbit_xml, scene, sizeof scene);
    const char *a[] = {"render", scene, "-o", fixture_path(&f, "orbit-###.exr", pattern, sizeof pattern), "--frames",
                       "0:30:15", "-D", "spp=4", "--threads", "2", NULL};
    cr_assert_eq(run_celadon(&f, a, err, sizeof err), 0, "%s", err);
    cr_expect_eq(access(fixture_path(&f, "orbit-000.exr", path, sizeof path), F_OK), 0);
    cr_expect_neq(access(fixture_path(&f, "orbit-030.exr", path, sizeof path), F_OK), 0, "frame B was rendered");
    const char *b[] = {"render", scene, "-o", fixture_path(&f, "one.exr", one, sizeof one), "-D", "frame=15", "-D",
                       "spp=4", NULL};
    cr_assert_eq(run_celadon(&f, b, err, sizeof err), 0, "%s", err);
    image_t f0 = read_image(fixture_path(&f, "orbit-000.exr", path, sizeof path));
    image_t f15 = read_image(fixture_path(&f, "orbit-015.exr", path, sizeof path)), o = read_image(one);
    double worst;
    cr_expect(same_within_rounding(&f15, &o, &worst), "frame 15 differs from -D frame=15 by %g", worst);
    cr_expect(!same_within_rounding(&f0, &f15, &worst), "frames 0 and 15 are the same image");
    image_free(&f0), image_free(&f15), image_free(&o);
    /* An output name without # for the frame, or a scene without $frame. */
    const char *c[] = {"render", scene, "-o", one, "--frames", "0:2", NULL};
    cr_expect_eq(run_celadon(&f, c, err, sizeof err), 2, "%s", err);
    cr_expect_not_null(strstr(err, "run of #"), "%s", err);
    render_fixture_close(&f);
}

/* The crosscheck's renders as two parts each, merged, measure what one
 * crosscheck run measures (within float rounding). */
Test(parts, crosscheck_from_parts_measures_the_same, .timeout = 300)
{
    render_fixture f;
    char scene[256], d1[256], d2[256], whole[256], merged[256], path[512], err[8192];
    render_fixture_with_scene(&f, "plum", orbit_xml, scene, sizeof scene);
    const char *common[] = {"--segments", "8,16", "-D", "spp=6", "--threads", "2", "--grid", "2"};
    const char *dirs[] = {fixture_path(&f, "p1", d1, sizeof d1), fixture_path(&f, "p2", d2, sizeof d2),
                          fixture_path(&f, "whole", whole, sizeof whole), fixture_path(&f, "merged", merged, sizeof merged)};
    for (int run = 0; run < 4; run++) {
        const char *args[24] = {"crosscheck", scene, "-o", dirs[run]};
        int n = 4;
        for (int i = 0; i < 8; i++)
            args[n++] = common[i];
        if (run < 2)
            args[n++] = "--part", args[n++] = run == 0 ? "1/2" : "2/2";
        if (run == 3)
            args[n++] = "--merge", args[n++] = d1, args[n++] = d2;
        args[n] = NULL;
        cr_assert_eq(run_celadon(&f, args, err, sizeof err), 0, "%s", err);
    }
    json_error_t je;
    snprintf(path, sizeof path, "%s/report.json", whole);
    json_t *a = json_load_file(path, 0, &je);
    snprintf(path, sizeof path, "%s/report.json", merged);
    json_t *b = json_load_file(path, 0, &je);
    cr_assert(a && b, "%s", je.text);
    json_t *ra = json_object_get(a, "segments"), *rb = json_object_get(b, "segments");
    cr_assert_eq(json_array_size(ra), 2);
    cr_assert_eq(json_array_size(rb), 2);
    static const char *const metrics[] = {"rel_mse", "mean_abs_diff", "coverage_area", "depth_rel_err",
                                          "normal_err_deg"};
    for (size_t i = 0; i < 2; i++)
        for (int m = 0; m < 5; m++) {
            double x = json_number_value(json_object_get(json_array_get(ra, i), metrics[m]));
            double y = json_number_value(json_object_get(json_array_get(rb, i), metrics[m]));
            cr_expect(fabs(x - y) <= 1e-5 * fabs(x), "%s of row %zu: %g whole, %g from parts", metrics[m], i, x, y);
        }
    json_decref(a), json_decref(b);
    /* One part's folder alone is refused: the other part is missing. */
    const char *lone[] = {"crosscheck", scene, "-o", merged, "--segments", "8,16", "-D", "spp=6", "--merge", d1, NULL};
    cr_expect_eq(run_celadon(&f, lone, err, sizeof err), 2, "%s", err);
    cr_expect_not_null(strstr(err, "missing: 2/2"), "%s", err);
    render_fixture_close(&f);
}
