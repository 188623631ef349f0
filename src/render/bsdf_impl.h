/* Private BSDF layout and helpers shared by the bsdf_*.c files. */
#ifndef CELADON_BSDF_IMPL_H
#define CELADON_BSDF_IMPL_H

#include "celadon/bsdf.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

typedef struct {
    int (*sample)(const bsdf_t *b, const bsdf_query *q, double u1, vec2 u2, bsdf_sample_rec *out);
    rgb (*eval)(const bsdf_t *b, const bsdf_query *q, vec3 wo);
    double (*pdf)(const bsdf_t *b, const bsdf_query *q, vec3 wo);
    rgb (*albedo)(const bsdf_t *b, vec2 uv);
    rgb (*straight)(const bsdf_t *b, const bsdf_query *q); /* NULL unless BSDF_STRAIGHT_TRANSMISSION */
} bsdf_ops;

struct bsdf {
    const char *plugin;
    const bsdf_ops *ops;
    unsigned flags;
    void *data; /* the plugin's parameters, allocated together with the struct */
};

/* One allocation holding the bsdf and data_size zeroed bytes of plugin data. */
bsdf_t *bsdf_alloc(const char *plugin, const bsdf_ops *ops, unsigned flags, size_t data_size, char *err,
                   size_t errlen);

static inline rgb spectrum_eval(const bsdf_spectrum *s, vec2 uv)
{
    return s->texture ? texture_eval(s->texture, uv) : s->value;
}
static inline double spectrum_mean(const bsdf_spectrum *s)
{
    return rgb_mean(s->texture ? texture_mean(s->texture) : s->value);
}

/* eval and pdf of BSDFs made only of delta lobes: always zero. */
rgb bsdf_eval_delta_only(const bsdf_t *b, const bsdf_query *q, vec3 wo);
double bsdf_pdf_delta_only(const bsdf_t *b, const bsdf_query *q, vec3 wo);

/* Validation: 0 if fine, else -1 with err naming the parameter. */
int bsdf_check_ior(double int_ior, double ext_ior, char *err, size_t errlen);
int bsdf_check_alpha(const char *name, double alpha, char *err, size_t errlen);
int bsdf_check_spectrum(const char *name, const bsdf_spectrum *s, char *err, size_t errlen);

/* Rough-BSDF sampling epilogue: fills weight = eval / pdf from the BSDF's own
 * eval and pdf, rejecting a zero density. */
int bsdf_finish_sample(const bsdf_t *b, const bsdf_query *q, bsdf_sample_rec *out);

#endif
