#include "core/record.h"

#include <stdlib.h>
#include <string.h>

void *record_alloc(size_t head_size, const void *data, size_t data_size, void **data_at)
{
    /* Round the head up so the data that follows is aligned for any type. */
    size_t head = (head_size + 15u) & ~(size_t)15u;
    char *r = calloc(1, head + data_size);
    if (!r)
        return NULL;
    *data_at = r + head;
    if (data)
        memcpy(r + head, data, data_size);
    return r;
}
