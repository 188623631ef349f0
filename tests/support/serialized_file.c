#include "serialized_file.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

typedef struct {
    unsigned char *b;
    size_t n, cap;
} bytes;

static void put_bytes(bytes *o, const void *p, size_t n)
{
    if (o->n + n > o->cap) {
        o->cap = 2 * (o->n + n);
        o->b = realloc(o->b, o->cap);
        if (!o->b)
            abort();
    }
    memcpy(o->b + o->n, p, n);
    o->n += n;
}

static void put_le(bytes *o, uint64_t v, int size)
{
    unsigned char b[8];
    for (int i = 0; i < size; i++)
        b[i] = (unsigned char)(v >> (8 * i));
    put_bytes(o, b, (size_t)size);
}

static void put_real(bytes *o, double v, int dbl)
{
    if (dbl) {
        uint64_t u;
        memcpy(&u, &v, 8);
        put_le(o, u, 8);
    } else {
        float f = (float)v;
        uint32_t u;
        memcpy(&u, &f, 4);
        put_le(o, u, 4);
    }
}

static void put_mesh(bytes *file, int version, int k, int dbl, unsigned flags, int level)
{
    enum { NV = SERIALIZED_FILE_NV };
    bytes raw = {0};
    put_le(&raw, flags | (dbl ? 0x2000u : 0x1000u), 4);
    if (version == 4)
        put_bytes(&raw, "mesh", 5);
    put_le(&raw, NV, 8);
    put_le(&raw, NV - 2, 8);
    for (int i = 0; i < NV; i++) {
        put_real(&raw, i, dbl);
        put_real(&raw, i * i + k, dbl);
        put_real(&raw, -i / 4.0, dbl);
    }
    for (int i = 0; (flags & SERIALIZED_FILE_NORMALS) && i < NV; i++)
        for (int c = 0; c < 3; c++)
            put_real(&raw, c == 2, dbl);
    for (int i = 0; (flags & SERIALIZED_FILE_UVS) && i < NV; i++) {
        put_real(&raw, i / 8.0, dbl);
        put_real(&raw, 1 - i / 8.0, dbl);
    }
    for (int i = 0; (flags & SERIALIZED_FILE_COLORS) && i < NV; i++)
        for (int c = 0; c < 3; c++)
            put_real(&raw, 0.5, dbl);
    for (int t = 0; t < NV - 2; t++) {
        put_le(&raw, 0, 4);
        put_le(&raw, (uint64_t)t + 1, 4);
        put_le(&raw, (uint64_t)t + 2, 4);
    }
    uLongf zn = compressBound(raw.n);
    unsigned char *z = malloc(zn);
    if (!z || compress2(z, &zn, raw.b, raw.n, level) != Z_OK)
        abort();
    put_le(file, 0x041C, 2);
    put_le(file, (uint64_t)version, 2);
    put_bytes(file, z, zn);
    free(z);
    free(raw.b);
}

unsigned char *serialized_file_bytes(int version, int nmeshes, int dbl, unsigned flags, int level, size_t *len)
{
    bytes f = {0};
    uint64_t off[4];
    if (nmeshes < 1 || nmeshes > 4)
        abort();
    for (int k = 0; k < nmeshes; k++) {
        off[k] = f.n;
        put_mesh(&f, version, k, dbl, flags, level);
    }
    for (int k = 0; k < nmeshes; k++)
        put_le(&f, off[k], version == 4 ? 8 : 4);
    put_le(&f, (uint64_t)nmeshes, 4);
    *len = f.n;
    return f.b;
}

int serialized_file_write(const char *path, int version, int nmeshes, int dbl, unsigned flags, int level)
{
    size_t n;
    unsigned char *b = serialized_file_bytes(version, nmeshes, dbl, flags, level, &n);
    FILE *fp = fopen(path, "wb");
    int ok = fp && fwrite(b, 1, n, fp) == n;
    if (fp && fclose(fp) != 0)
        ok = 0;
    free(b);
    return ok ? 0 : -1;
}
