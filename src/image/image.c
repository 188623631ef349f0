#include "celadon/image.h"

#include <stdlib.h>

image_t image_alloc(int width, int height, int channels)
{
    image_t img = {width, height, channels, 8, 0, NULL};
    img.data = calloc((size_t)width * (size_t)height * (size_t)channels, sizeof(float));
    return img;
}

void image_free(image_t *img)
{
    free(img->data);
    img->data = NULL;
}

float *image_to_gray(const image_t *img)
{
    size_t n = (size_t)img->width * (size_t)img->height;
    float *g = malloc(n * sizeof *g);
    if (!g)
        return NULL;
    int c = img->channels;
    int color = c >= 3;
    for (size_t i = 0; i < n; i++) {
        const float *p = img->data + i * (size_t)c;
        g[i] = color ? 0.299f * p[0] + 0.587f * p[1] + 0.114f * p[2] : p[0];
    }
    return g;
}
