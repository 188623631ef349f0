/* A record and its plugin's data in one allocation: what every plugin kind's
 * handle (a BSDF, a texture, an emitter, ...) is made of. */
#ifndef CELADON_RECORD_H
#define CELADON_RECORD_H

#include <stddef.h>

/* Allocates head_size zeroed bytes followed, suitably aligned, by a copy of
 * data_size bytes of data (zeroed when data is NULL), which *data_at then
 * points to. Free the record with free(). NULL when out of memory. */
void *record_alloc(size_t head_size, const void *data, size_t data_size, void **data_at);

#endif
