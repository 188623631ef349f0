#include "shared_data.h"

#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/stat.h>

void shared_data_path(char *out, size_t len, const char *rel)
{
    const char *shared = getenv("CELADON_SHARED");
    snprintf(out, len, "%s/%s", shared && *shared ? shared : "../shared", rel);
}

void shared_data_require(const char *path)
{
    struct stat st;
    if (stat(path, &st) == 0)
        return;
    const char *required = getenv("CELADON_REQUIRE_DATA");
    if (required && *required)
        cr_assert_fail("shared data missing: %s (CELADON_REQUIRE_DATA is set; set CELADON_SHARED)", path);
    cr_skip_test("shared data missing: %s (set CELADON_SHARED)", path);
}
