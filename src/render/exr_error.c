#include "render/exr_error.h"

#include <stdio.h>

static _Thread_local char exr_message[256];

void exr_error_remember(exr_const_context_t ctxt, exr_result_t code, const char *msg)
{
    (void)ctxt;
    snprintf(exr_message, sizeof exr_message, "%s", msg ? msg : exr_get_default_error_message(code));
}

void exr_error_clear(void) { exr_message[0] = '\0'; }

const char *exr_error_text(exr_result_t rv) { return exr_message[0] ? exr_message : exr_get_default_error_message(rv); }
