/* image_read_checked: the checks a photo passes before and while it is
 * decoded, with libpng's own stderr lines kept out of the user's terminal;
 * image_read_quiet: the same decode without the checks (a scene's
 * textures and environment maps). */
#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "celadon/image.h"

/* Copies the captured text to stderr, leaving out libpng's own lines. */
static void replay_captured(FILE *cap)
{
    char line[1024];
    rewind(cap);
    while (fgets(line, sizeof line, cap))
        if (strncmp(line, "libpng ", 7) != 0)
            fputs(line, stderr);
}

/* libpng (inside OpenImageIO) prints "libpng error: ..." on stderr for a
 * damaged PNG, on top of the error OpenImageIO returns; that would break the
 * one-line-per-bad-photo rule. So probing and decoding run with stderr
 * captured in a temporary file, replayed afterwards without libpng's lines.
 * Serialised: stderr is one per process. */
static int read_quietly(const char *path, image_t *img, int *w, int *h, char *err, size_t errlen)
{
    int rc;
#pragma omp critical(celadon_stderr)
    {
        fflush(stderr);
        FILE *cap = tmpfile();
        int saved = cap ? dup(2) : -1;
        int captured = saved >= 0 && dup2(fileno(cap), 2) >= 0;
        int ch;
        rc = img ? image_read(path, img, err, errlen) : image_probe(path, w, h, &ch, err, errlen);
        if (captured) {
            fflush(stderr);
            dup2(saved, 2);
            replay_captured(cap);
        }
        if (saved >= 0)
            close(saved);
        if (cap)
            fclose(cap);
    }
    return rc;
}

int image_read_quiet(const char *path, image_t *img, char *err, size_t errlen)
{
    return read_quietly(path, img, NULL, NULL, err, errlen);
}

int image_read_checked(const char *path, int min_side, double max_megapixels, image_t *img, char *err,
                       size_t errlen)
{
    struct stat st;
    char why[400];
    if (stat(path, &st) != 0) {
        snprintf(err, errlen, "cannot open: %s", strerror(errno));
        return -1;
    }
    if (S_ISDIR(st.st_mode)) {
        snprintf(err, errlen, "is a folder, not a photo");
        return -1;
    }
    if (!S_ISREG(st.st_mode)) {
        snprintf(err, errlen, "not a regular file");
        return -1;
    }
    if (st.st_size == 0) {
        snprintf(err, errlen, "empty file");
        return -1;
    }
    if (access(path, R_OK) != 0) {
        snprintf(err, errlen, "cannot read: %s", strerror(errno));
        return -1;
    }
    int w, h;
    if (read_quietly(path, NULL, &w, &h, why, sizeof why) != 0) {
        snprintf(err, errlen, "not a readable image (%s)", why);
        return -1;
    }
    if (w < min_side || h < min_side) {
        snprintf(err, errlen, "image too small (%dx%d; at least %dx%d needed)", w, h, min_side, min_side);
        return -1;
    }
    if ((double)w * h > max_megapixels * 1e6) {
        snprintf(err, errlen, "image too large (%dx%d; at most %.0f megapixels)", w, h, max_megapixels);
        return -1;
    }
    if (read_quietly(path, img, NULL, NULL, why, sizeof why) != 0) {
        snprintf(err, errlen, "cannot decode the image (%s)", why);
        return -1;
    }
    return 0;
}
