/* A nested BSDF in a perturbed shading frame: what normalmap and bumpmap
 * share (bsdf_impl.h). The nested BSDF sees the query moved into the frame
 * (wi, and the surface's derivatives and geometric normal); a rotation
 * keeps solid angles, so densities carry over unchanged. */
#include "bsdfs/bsdf_impl.h"

vec3 bsdf_query_tangent(const bsdf_query *q)
{
    vec3 t = v3(q->dpdu.x, q->dpdu.y, 0.0);
    double len = v3_len(t);
    return len > 1e-300 ? v3_scale(t, 1.0 / len) : v3(1.0, 0.0, 0.0);
}

/* The plugin's frame at q: its normal, mirrored when wi sees it from
 * behind, and the tangent made perpendicular to it (Gram-Schmidt). */
static frame3 frame_at(const bsdf_perturbing *d, const bsdf_query *q)
{
    vec3 n, tangent;
    d->normal(d, q, &n, &tangent);
    if (!(v3_len(n) > 1e-300)) /* no perturbation to speak of */
        n = v3(0.0, 0.0, 1.0);
    if (d->flip_invalid && q->wi.z * v3_dot(q->wi, n) <= 0.0)
        n = v3(-n.x, -n.y, n.z);
    frame3 f;
    f.n = v3_norm(n);
    vec3 s = v3_sub(tangent, v3_scale(f.n, v3_dot(f.n, tangent)));
    if (!(v3_len(s) > 1e-12)) /* the tangent along the normal: any perpendicular will do */
        return frame3_from_normal(f.n);
    f.s = v3_norm(s);
    f.t = v3_cross(f.n, f.s);
    return f;
}

/* The query as the nested BSDF sees it in the frame. */
static bsdf_query moved(frame3 f, const bsdf_query *q)
{
    bsdf_query r = *q;
    r.wi = frame3_to_local(f, q->wi);
    r.dpdu = frame3_to_local(f, q->dpdu);
    r.dpdv = frame3_to_local(f, q->dpdv);
    r.ng = frame3_to_local(f, q->ng);
    return r;
}

/* Estevez et al. 2019: G = 2 / (1 + sqrt(1 + a^2 tan^2 theta_o)),
 * a^2 = min(tan^2 theta_n / 8, 1), theta_n the perturbed normal's angle. */
static double shadow_terminator(vec3 n, vec3 wo)
{
    double tan2_n = (1.0 - n.z * n.z) / (n.z * n.z), tan2_o = (1.0 - wo.z * wo.z) / (wo.z * wo.z);
    double a2 = fmin(0.125 * tan2_n, 1.0);
    double g = 2.0 / (1.0 + sqrt(1.0 + a2 * tan2_o));
    return isfinite(g) ? g : 0.0;
}

int bsdf_perturbing_sample(const bsdf_t *b, const bsdf_query *q, double u1, vec2 u2, bsdf_sample_rec *out)
{
    const bsdf_perturbing *d = b->data;
    frame3 f = frame_at(d, q);
    bsdf_query r = moved(f, q);
    if (!bsdf_sample(d->nested, &r, u1, u2, out) || rgb_is_black(out->weight))
        return 0;
    vec3 wo = frame3_to_world(f, out->wo);
    if (out->wo.z * wo.z <= 0.0)
        return 0;
    out->wo = wo;
    if (d->shadowing)
        out->weight = rgb_scale(out->weight, shadow_terminator(f.n, wo));
    return 1;
}

rgb bsdf_perturbing_eval(const bsdf_t *b, const bsdf_query *q, vec3 wo)
{
    const bsdf_perturbing *d = b->data;
    frame3 f = frame_at(d, q);
    vec3 local = frame3_to_local(f, wo);
    if (local.z * wo.z <= 0.0)
        return rgb_gray(0.0);
    bsdf_query r = moved(f, q);
    rgb value = bsdf_eval(d->nested, &r, local);
    return d->shadowing ? rgb_scale(value, shadow_terminator(f.n, wo)) : value;
}

double bsdf_perturbing_pdf(const bsdf_t *b, const bsdf_query *q, vec3 wo)
{
    const bsdf_perturbing *d = b->data;
    frame3 f = frame_at(d, q);
    vec3 local = frame3_to_local(f, wo);
    if (local.z * wo.z <= 0.0)
        return 0.0;
    bsdf_query r = moved(f, q);
    return bsdf_pdf(d->nested, &r, local);
}

rgb bsdf_perturbing_albedo(const bsdf_t *b, texture_point uv)
{
    const bsdf_perturbing *d = b->data;
    return bsdf_albedo_at(d->nested, uv);
}

vec3 bsdf_perturbing_shading_normal(const bsdf_t *b, const bsdf_query *q)
{
    return frame_at(b->data, q).n;
}

int bsdf_perturbing_param(bsdf_set *set, scene_obj *o, bsdf_perturbing *d, char *err, size_t errlen)
{
    if (!(d->nested = bsdf_set_get(set, scene_obj_child(o, SCENE_BSDF), err, errlen)))
        return -1;
    d->flip_invalid = scene_obj_bool(o, "flip_invalid_normals", true);
    d->shadowing = scene_obj_bool(o, "use_shadowing_function", true);
    return 0;
}
