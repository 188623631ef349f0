/* Mitsuba's `independent` sampler: every number of every pixel sample
 * uniform and independent, from the PCG32 stream rng_for_sample(seed, x, y,
 * sample) (`sample_count` 4 and `seed` 0 by default). Dimensions do not
 * matter to it: it draws in the order asked. */
#include "samplers/sampler_impl.h"

static void independent_prepare(sampler_t *s, int width, int height)
{
    (void)s, (void)width, (void)height;
}

static void independent_start(sampler_stream *st)
{
    st->rng = rng_for_sample(st->sampler->seed, st->px, st->py, st->index);
}

static double independent_next_1d(sampler_stream *st)
{
    st->dim++;
    return rng_next_double(&st->rng);
}

/* The second coordinate is drawn first: the order in which the renderer has
 * always drawn the pairs (GCC evaluated its v2(rng(), rng()) right to left). */
static vec2 independent_next_2d(sampler_stream *st)
{
    st->dim += 2;
    double y = rng_next_double(&st->rng);
    double x = rng_next_double(&st->rng);
    return v2(x, y);
}

static const sampler_ops independent_ops = {independent_prepare, independent_start, independent_next_1d,
                                            independent_next_2d};

static int independent_create(scene_obj *o, sampler_t *out, char *err, size_t errlen)
{
    (void)err, (void)errlen;
    out->ops = &independent_ops;
    sampler_read_common(o, false, out);
    out->in_order = true;
    return 0;
}

static const scene_param_decl independent_params[] = {SAMPLER_PARAMS_COMMON, SAMPLER_PARAMS_END};

const sampler_plugin sampler_independent = {
    .decl = {.cls = SCENE_SAMPLER, .type = "independent", .params = independent_params},
    .create = independent_create,
};
