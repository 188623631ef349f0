#include "celadon/version.h"

const char *celadon_version(void) { return CELADON_VERSION; }
