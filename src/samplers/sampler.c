/* Dispatch to the scene's sampler plugin. */
#include "samplers/sampler_impl.h"

void sampler_start(const sampler_t *s, sampler_stream *st, uint32_t px, uint32_t py, uint32_t index)
{
    st->sampler = s;
    st->px = px, st->py = py, st->index = index;
    s->ops->start(st);
}

double sampler_next_1d(sampler_stream *st)
{
    return st->sampler->ops->next_1d(st);
}

vec2 sampler_next_2d(sampler_stream *st)
{
    return st->sampler->ops->next_2d(st);
}
