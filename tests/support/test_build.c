#include "test_build.h"

bool test_build_is_sanitized(void)
{
#ifdef __SANITIZE_ADDRESS__
    return true;
#else
    return false;
#endif
}

int test_build_case_step(int share) { return test_build_is_sanitized() && share > 1 ? share : 1; }

int test_build_share(int n, int share)
{
    int m = test_build_is_sanitized() && share > 1 ? n / share : n;
    return m > 0 ? m : 1;
}
