/* JPEG encoding in memory with libjpeg(-turbo): the vessels' textures in
 * museum.glb (a seventh of their PNG's bytes at quality 85). */
#ifndef CELADON_MUSEUM_JPEG_MEMORY_H
#define CELADON_MUSEUM_JPEG_MEMORY_H

#include <stddef.h>
#include <stdint.h>

/* Encodes width x height 8-bit RGB pixels (rows top down) at quality
 * 1..100; *jpeg (malloc'd) receives the file's bytes. Returns 0 or -1. */
int jpeg_encode_rgb(const uint8_t *rgb, int width, int height, int quality, uint8_t **jpeg, size_t *len);

#endif
