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
