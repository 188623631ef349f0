/* The film: accumulation, bit-exact EXR round trip (read back plane by plane
 * through the OpenEXR core API), sRGB tonemapping, atomic output. */
#include <criterion/criterion.h>
#include <dirent.h>
#include <ftw.h>
#include <math.h>
#include <openexr.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "celadon/film.h"
#include "celadon/image.h"
#include "celadon/render.h"
#include "celadon/scene.h"
#include "support/exr_planes.h"

static char dir[64];

static void make_dir(void)
{
    snprintf(dir, sizeof dir, "/tmp/celadon-film-XXXXXX");
    cr_assert_not_null(mkdtemp(dir));
}

static int rm_entry(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
    (void)st, (void)flag, (void)ftw;
    return remove(path);
}

static void remove_dir(void) { nftw(dir, rm_entry, 8, FTW_DEPTH | FTW_PHYS); }

TestSuite(film, .init = make_dir, .fini = remove_dir);

static int count_entries(void)
{
    DIR *d = opendir(dir);
    cr_assert_not_null(d);
    int n = 0;
    for (struct dirent *e; (e = readdir(d));)
        n += strcmp(e->d_name, ".") != 0 && strcmp(e->d_name, "..") != 0;
    closedir(d);
    return n;
}

Test(film, averages_weights_and_merges)
{
    film_t a, b;
    char err[256];
    static const char *const t[1] = {"T"};
    const film_aov aov[] = {{"depth", 1, t}};
    cr_assert_eq(film_init(&a, 4, 3, aov, 1, err, sizeof err), 0, "%s", err);
    cr_assert_eq(film_init(&b, 4, 3, aov, 1, err, sizeof err), 0);
    cr_assert_eq(a.nchannels, 4);
    cr_assert_str_eq(a.names[3], "depth.T", "Mitsuba's name, not .Y (which EXR readers take for luminance)");
    const double s1[4] = {1, 2, 3, 10}, s2[4] = {4, 0, 0, 20};
    film_add(&a, 2, 1, s1, 1.0);
    film_add(&b, 2, 1, s2, 3.0); /* weighted 3:1 */
    film_merge(&a, &b);
    float px[4 * 3 * 4];
    film_develop(&a, px);
    const float *p = px + (1 * 4 + 2) * 4;
    cr_assert_float_eq(p[0], (1 + 12) / 4.0, 1e-6);
    cr_assert_float_eq(p[1], 2 / 4.0, 1e-6);
    cr_assert_float_eq(p[3], (10 + 60) / 4.0, 1e-6);
    for (int i = 0; i < 4 * 3 * 4; i++)
        if (i / 4 != 1 * 4 + 2)
            cr_assert_eq(px[i], 0.0f, "unsampled pixels are black");
    film_free(&a);
    film_free(&b);
    const film_aov bad[] = {{"x", 2, NULL}};
    cr_assert_eq(film_init(&a, 4, 3, bad, 1, err, sizeof err), -1);
    /* channels written under one name twice: refused before any render */
    static const char *const z[1] = {"Z"}, *const y[1] = {"Y"}, *const none[1] = {""};
    const film_aov depth_z[] = {{"Z", 1, none}};
    cr_assert_eq(film_init_format(&a, 4, 3, FILM_XYZ, depth_z, 1, err, sizeof err), -1);
    cr_expect_str_eq(err, "the channel 'Z' of AOV 'Z' is written twice on a xyz film");
    cr_assert_eq(film_init_format(&a, 4, 3, FILM_RGB, depth_z, 1, err, sizeof err), 0, "%s", err);
    film_free(&a);
    const film_aov twice[] = {{"Depth", 1, z}, {"Depth", 1, z}}, lum[] = {{"", 1, y}};
    cr_assert_eq(film_init(&a, 4, 3, twice, 2, err, sizeof err), -1);
    cr_assert_eq(film_init_format(&a, 4, 3, FILM_LUMINANCE_ALPHA, lum, 1, err, sizeof err), -1);
    cr_assert_eq(film_init_format(&a, 4, 3, FILM_XYZA, twice, 1, err, sizeof err), 0, "%s", err);
    film_free(&a);
    cr_assert_eq(film_init(&a, 0, 3, NULL, 0, err, sizeof err), -1);
}

Test(film, exr_float32_round_trip_is_exact)
{
    /* 37 rows: several ZIP chunks of 16 lines, the last one partial. */
    const int w = 23, h = 37;
    const film_aov aovs[] = {{"albedo", 3, NULL}, {"depth", 1, NULL}};
    film_t f;
    char err[256], path[128];
    cr_assert_eq(film_init(&f, w, h, aovs, 2, err, sizeof err), 0);
    cr_assert_eq(f.nchannels, 7);
    srand(7);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            if ((x + y) % 11 == 0)
                continue; /* some pixels left unsampled, as after Ctrl-C */
            double v[7];
            for (int c = 0; c < 7; c++)
                v[c] = ((double)rand() / RAND_MAX - 0.2) * pow(10.0, (rand() % 9) - 4) + 0.001 * c;
            film_add(&f, x, y, v, 0.25 + (x % 3));
        }
    float *want = malloc(sizeof(float) * w * h * 7);
    film_develop(&f, want);
    snprintf(path, sizeof path, "%s/out.exr", dir);
    cr_assert_eq(film_write(&f, path, err, sizeof err), 0, "%s", err);
    cr_assert_eq(count_entries(), 1, "no temporary file left");

    exr_planes e;
    read_exr(path, &e);
    cr_assert_eq(e.width, w);
    cr_assert_eq(e.height, h);
    cr_assert_eq(e.nch, 7);
    for (int c = 0; c < 7; c++) {
        int k = 0;
        while (k < e.nch && strcmp(e.names[k], f.names[c]) != 0)
            k++;
        cr_assert_lt(k, e.nch, "channel %s missing", f.names[c]);
        for (int p = 0; p < w * h; p++)
            cr_assert(memcmp(&e.planes[k][p], &want[p * 7 + c], sizeof(float)) == 0,
                      "channel %s pixel %d: %.9g != %.9g", f.names[c], p, e.planes[k][p], want[p * 7 + c]);
    }
    for (int c = 0; c < e.nch; c++)
        free(e.planes[c]);
    free(want);
    film_free(&f);
}

Test(film, srgb_tonemap)
{
    cr_assert_eq(film_srgb8(0.5), 188);
    cr_assert_eq(film_srgb8(0.0), 0);
    cr_assert_eq(film_srgb8(-3.0), 0);
    cr_assert_eq(film_srgb8(NAN), 0);
    cr_assert_eq(film_srgb8(1.0), 255);
    cr_assert_eq(film_srgb8(7.0), 255);
    cr_assert_eq(film_srgb8(0.002), 7, "linear toe: 12.92 * 0.002 * 255 = 6.6");
    cr_assert_eq(film_srgb8(0.18), 118, "middle gray");

    film_t f;
    char err[256], path[128];
    cr_assert_eq(film_init(&f, 2, 1, NULL, 0, err, sizeof err), 0);
    const double half[3] = {0.5, 0.5, 0.5}, hot[3] = {4, 0.18, -1};
    film_add(&f, 0, 0, half, 1);
    film_add(&f, 1, 0, hot, 1);
    uint8_t rgb8[6];
    film_develop_srgb8(&f, rgb8);
    const uint8_t want[6] = {188, 188, 188, 255, 118, 0};
    cr_assert_arr_eq(rgb8, want, 6);
    /* film_write hands exactly these bytes to image_write_u8. Decoding the
     * PNG back is left out: image_read reads 8-bit files into a buffer sized
     * for 8-bit pixels as floats (reported to the integrator). */
    snprintf(path, sizeof path, "%s/out.png", dir);
    cr_assert_eq(film_write(&f, path, err, sizeof err), 0, "%s", err);
    int w, h, ch;
    cr_assert_eq(image_probe(path, &w, &h, &ch, err, sizeof err), 0, "%s", err);
    cr_assert(w == 2 && h == 1 && ch == 3);
    cr_assert_eq(count_entries(), 1, "no temporary file left");
    film_free(&f);
}

Test(film, failed_writes_leave_nothing)
{
    film_t f;
    char err[256], path[128];
    cr_assert_eq(film_init(&f, 3, 2, NULL, 0, err, sizeof err), 0);
    /* The final names are directories: the rename fails after the data was
     * written to a temporary file, which must then be gone. */
    const char *names[] = {"busy.exr", "busy.png"};
    for (int i = 0; i < 2; i++) {
        snprintf(path, sizeof path, "%s/%s", dir, names[i]);
        cr_assert_eq(mkdir(path, 0755), 0);
        cr_assert_eq(film_write(&f, path, err, sizeof err), -1);
        cr_assert_not_null(strstr(err, path), "%s", err);
    }
    cr_assert_eq(count_entries(), 2, "only the two directories");
    snprintf(path, sizeof path, "%s/missing/out.exr", dir);
    cr_assert_eq(film_write(&f, path, err, sizeof err), -1);
    snprintf(path, sizeof path, "%s/out.bmp", dir);
    cr_assert_eq(film_write(&f, path, err, sizeof err), -1);
    cr_assert_not_null(strstr(err, "must end in .exr, .hdr, .tif"), "%s", err);
    cr_assert_eq(count_entries(), 2);
    film_free(&f);
}

/* Renders a constant environment of radiance (0.2, 0.5, 0.7) through a
 * film of the given pixel format into dir/name. */
static void render_environment(const char *format, const char *name, char *path, size_t len)
{
    char xml[1024], scene[160], err[1024];
    snprintf(scene, sizeof scene, "%s/%s.xml", dir, name);
    snprintf(xml, sizeof xml,
             "<scene version=\"3.0.0\"><sensor type=\"perspective\"><float name=\"fov\" value=\"30\"/>"
             "<transform name=\"to_world\"><translate x=\"1\" y=\"2\" z=\"3\"/></transform>"
             "<sampler type=\"independent\"><integer name=\"sample_count\" value=\"3\"/>"
             "<integer name=\"seed\" value=\"12345678901\"/></sampler>"
             "<film type=\"hdrfilm\"><integer name=\"width\" value=\"4\"/><integer name=\"height\" value=\"2\"/>"
             "<string name=\"pixel_format\" value=\"%s\"/></film></sensor>"
             "<emitter type=\"constant\"><rgb name=\"radiance\" value=\"0.2, 0.5, 0.7\"/></emitter></scene>",
             format);
    FILE *f = fopen(scene, "w");
    cr_assert_not_null(f);
    fputs(xml, f);
    fclose(f);
    scene_t *s = scene_create_from_file(scene, NULL, 0, NULL, err, sizeof err);
    cr_assert_not_null(s, "%s", err);
    film_t film;
    render_options ro = {.threads = 1};
    cr_assert_eq(render_scene(s, &ro, &film, NULL, err, sizeof err), 0, "%s", err);
    snprintf(path, len, "%s/%s.exr", dir, name);
    cr_assert_eq(film_write(&film, path, err, sizeof err), 0, "%s", err);
    film_free(&film);
    scene_destroy(s);
}

/* hdrfilm's pixel formats as the EXR stores them, against the colour
 * conversions (Rec. 709 primaries, D65) written out here, and the header's
 * record of how the image was made. */
Test(film, pixel_formats_and_metadata)
{
    const double r = 0.2, g = 0.5, b = 0.7;
    char path[256];
    exr_planes e;
    render_environment("luminance_alpha", "ya", path, sizeof path);
    read_exr(path, &e);
    cr_assert_eq(e.nch, 2, "Y and A");
    int y = plane_index(&e, "Y"), a = plane_index(&e, "A");
    for (int p = 0; p < 8; p++) {
        cr_assert_float_eq(e.planes[y][p], 0.212671 * r + 0.715160 * g + 0.072169 * b, 1e-6);
        cr_assert_eq(e.planes[a][p], 1.0f, "a visible environment covers the pixel");
    }
    for (int c = 0; c < e.nch; c++)
        free(e.planes[c]);
    render_environment("xyz", "xyz", path, sizeof path);
    read_exr(path, &e);
    cr_assert_eq(e.nch, 3);
    cr_assert_float_eq(e.planes[plane_index(&e, "X")][5], 0.412453 * r + 0.357580 * g + 0.180423 * b, 1e-6);
    cr_assert_float_eq(e.planes[plane_index(&e, "Z")][5], 0.019334 * r + 0.119193 * g + 0.950227 * b, 1e-6);
    for (int c = 0; c < e.nch; c++)
        free(e.planes[c]);
    /* The header: spp, the 64-bit seed, renderer, integrator, camera and its pose. */
    exr_context_t ctx;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    cr_assert_eq(exr_start_read(&ctx, path, &init), EXR_ERR_SUCCESS);
    int32_t spp, len;
    const char *str;
    cr_assert_eq(exr_attr_get_int(ctx, 0, "spp", &spp), EXR_ERR_SUCCESS);
    cr_assert_eq(spp, 3);
    cr_assert_eq(exr_attr_get_string(ctx, 0, "seed", &len, &str), EXR_ERR_SUCCESS);
    cr_assert(len == 11 && strncmp(str, "12345678901", 11) == 0, "seed %.*s", len, str);
    cr_assert_eq(exr_attr_get_string(ctx, 0, "renderer", &len, &str), EXR_ERR_SUCCESS);
    cr_assert(strncmp(str, "celadon", 7) == 0);
    cr_assert_eq(exr_attr_get_string(ctx, 0, "integrator", &len, &str), EXR_ERR_SUCCESS);
    cr_assert(len == 4 && strncmp(str, "path", 4) == 0, "integrator %.*s", len, str);
    cr_assert_eq(exr_attr_get_string(ctx, 0, "camera", &len, &str), EXR_ERR_SUCCESS);
    cr_assert(strncmp(str, "perspective fov_x=30 ", 21) == 0, "camera %.*s", len, str);
    /* worldToCamera (Imath: row vectors, camera looking down -z) maps the
     * camera's position to the origin and a point ahead of it (+z for
     * Mitsuba's camera, whose to_world here is a translation) to -z. */
    exr_attr_m44f_t m;
    cr_assert_eq(exr_attr_get_m44f(ctx, 0, "worldToCamera", &m), EXR_ERR_SUCCESS);
    const double pts[2][3] = {{1, 2, 3}, {1, 2, 5}};
    double out[2][3];
    for (int k = 0; k < 2; k++)
        for (int c = 0; c < 3; c++)
            out[k][c] = pts[k][0] * m.m[c] + pts[k][1] * m.m[4 + c] + pts[k][2] * m.m[8 + c] + m.m[12 + c];
    cr_assert(fabs(out[0][0]) + fabs(out[0][1]) + fabs(out[0][2]) < 1e-6, "the camera is the origin");
    cr_assert(fabs(out[1][0]) + fabs(out[1][1]) < 1e-6 && fabs(out[1][2] + 2.0) < 1e-6, "ahead is -z");
    exr_finish(&ctx);
}
