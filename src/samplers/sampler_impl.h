/* What a sampler plugin provides. Private to src/samplers/. */
#ifndef CELADON_SAMPLER_IMPL_H
#define CELADON_SAMPLER_IMPL_H

#include "samplers/samplers.h"

struct sampler_ops {
    /* Sets up st (its sampler, pixel and index are already set). */
    void (*start)(sampler_stream *st);
    double (*next_1d)(sampler_stream *st);
    vec2 (*next_2d)(sampler_stream *st);
};

#endif
