/* The OpenEXR core library's error details, which it reports through a
 * callback: the last one of this thread is kept for our one-line messages.
 * Private to src/render/ (exr_write.c, exr_read.c). */
#ifndef CELADON_EXR_ERROR_H
#define CELADON_EXR_ERROR_H

#include <openexr.h>

/* The context's error_handler_fn. */
void exr_error_remember(exr_const_context_t ctxt, exr_result_t code, const char *msg);
void exr_error_clear(void);
/* The last detail remembered since exr_error_clear, or rv's default text. */
const char *exr_error_text(exr_result_t rv);

#endif
