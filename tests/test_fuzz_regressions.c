/* The regression corpus of the fuzz targets (docs/faults.md): every input
 * that ever crashed or hung a target, under tests/data/fuzz-regressions/
 * TARGET/, run again through the same target as ordinary test cases (under
 * ASan+UBSan in the sanitized build). An input passes when the target
 * returns, whatever its verdict. */
#include <criterion/criterion.h>
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "support/fuzz_targets.h"

static unsigned char *slurp(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    cr_assert_not_null(f, "cannot open %s", path);
    cr_assert_eq(fseek(f, 0, SEEK_END), 0);
    long n = ftell(f);
    rewind(f);
    unsigned char *buf = malloc((size_t)n + 1);
    cr_assert_not_null(buf);
    cr_assert_eq(fread(buf, 1, (size_t)n, f), (size_t)n);
    fclose(f);
    *len = (size_t)n;
    return buf;
}

/* Runs every file of folder dir through the target; returns how many there
 * were, and how many it accepted in *accepted (may be NULL). */
static int run_folder(const char *target, const char *dir, int *accepted)
{
    const fuzz_target *t = fuzz_target_table;
    while (t->name && strcmp(t->name, target))
        t++;
    cr_assert_not_null(t->name, "no fuzz target '%s'", target);
    DIR *d = opendir(dir);
    cr_assert_not_null(d, "%s is missing (run the tests from the repository's top folder)", dir);
    int n = 0, ok = 0;
    for (struct dirent *e; (e = readdir(d));) {
        if (e->d_name[0] == '.')
            continue;
        char path[600];
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        size_t len;
        unsigned char *data = slurp(path, &len);
        ok += t->run(data, len) == 0;
        free(data);
        n++;
    }
    closedir(d);
    if (accepted)
        *accepted = ok;
    return n;
}

static int run_corpus(const char *target)
{
    char dir[256];
    snprintf(dir, sizeof dir, "tests/data/fuzz-regressions/%s", target);
    return run_folder(target, dir, NULL);
}

/* Each corpus holds at least the inputs the issue reported by hand. */
Test(fuzz_regressions, profile, .timeout = 120) { run_corpus("profile"); }
Test(fuzz_regressions, scene, .timeout = 120) { cr_expect_geq(run_corpus("scene"), 5); }
Test(fuzz_regressions, image, .timeout = 120) { cr_expect_geq(run_corpus("image"), 1); }
Test(fuzz_regressions, serialized, .timeout = 120) { run_corpus("serialized"); }
Test(fuzz_regressions, catalogue, .timeout = 120) { run_corpus("catalogue"); }

/* The serialized target's seeds (written by `make fuzz-seeds`) are files the
 * reader takes whole, so that fuzzing starts from the accepted path. */
Test(fuzz_regressions, serialized_seeds_are_accepted, .timeout = 120)
{
    int accepted, n = run_folder("serialized", "fuzz/seeds/serialized", &accepted);
    cr_expect_geq(n, 6);
    cr_expect_eq(accepted, n, "%d of the %d seeds refused", n - accepted, n);
}
