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

/* Reads every channel of an EXR into its own float plane (decoding plane by
 * plane: the 3.1 core API misorders interleaved RGBA decodes). */
typedef struct {
    int width, height, nch;
    char names[16][32];
    float *planes[16];
} exr_planes;

static void read_exr(const char *path, exr_planes *out)
{
    exr_context_t ctx;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    cr_assert_eq(exr_start_read(&ctx, path, &init), EXR_ERR_SUCCESS);
    exr_attr_box2i_t dw;
    cr_assert_eq(exr_get_data_window(ctx, 0, &dw), EXR_ERR_SUCCESS);
    out->width = dw.max.x - dw.min.x + 1;
    out->height = dw.max.y - dw.min.y + 1;
    const exr_attr_chlist_t *chl;
    cr_assert_eq(exr_get_channels(ctx, 0, &chl), EXR_ERR_SUCCESS);
    out->nch = chl->num_channels;
    cr_assert_leq(out->nch, 16);
    for (int c = 0; c < out->nch; c++) {
        snprintf(out->names[c], sizeof out->names[c], "%s", chl->entries[c].name.str);
        cr_assert_eq(chl->entries[c].pixel_type, EXR_PIXEL_FLOAT, "float32 on disk");
        out->planes[c] = calloc((size_t)out->width * out->height, sizeof(float));
    }
    int32_t lines;
    cr_assert_eq(exr_get_scanlines_per_chunk(ctx, 0, &lines), EXR_ERR_SUCCESS);
    exr_decode_pipeline_t dec = EXR_DECODE_PIPELINE_INITIALIZER;
    for (int y = dw.min.y, first = 1; y <= dw.max.y; y += lines, first = 0) {
        exr_chunk_info_t cinfo;
        cr_assert_eq(exr_read_scanline_chunk_info(ctx, 0, y, &cinfo), EXR_ERR_SUCCESS);
        cr_assert_eq(first ? exr_decoding_initialize(ctx, 0, &cinfo, &dec) : exr_decoding_update(ctx, 0, &cinfo, &dec),
                     EXR_ERR_SUCCESS);
        for (int c = 0; c < dec.channel_count; c++) {
            int k = 0;
            while (strcmp(out->names[k], dec.channels[c].channel_name) != 0)
                k++;
            dec.channels[c].decode_to_ptr = (uint8_t *)(out->planes[k] + (size_t)(cinfo.start_y - dw.min.y) * out->width);
            dec.channels[c].user_pixel_stride = sizeof(float);
            dec.channels[c].user_line_stride = out->width * (int32_t)sizeof(float);
            dec.channels[c].user_bytes_per_element = sizeof(float);
            dec.channels[c].user_data_type = EXR_PIXEL_FLOAT;
        }
        if (first)
            cr_assert_eq(exr_decoding_choose_default_routines(ctx, 0, &dec), EXR_ERR_SUCCESS);
        cr_assert_eq(exr_decoding_run(ctx, 0, &dec), EXR_ERR_SUCCESS);
    }
    exr_decoding_destroy(ctx, &dec);
    exr_finish(&ctx);
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
    snprintf(path, sizeof path, "%s/out.tif", dir);
    cr_assert_eq(film_write(&f, path, err, sizeof err), -1);
    cr_assert_not_null(strstr(err, "unsupported output format"), "%s", err);
    cr_assert_eq(count_entries(), 2);
    film_free(&f);
}
