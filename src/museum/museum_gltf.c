/* museum.glb: nodes, meshes, materials, lights and camera of the museum.
 * See museum_gltf.h. */
#include "museum/museum_gltf.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "museum/glb.h"
#include "museum/room_surfaces.h"

enum { SAMPLER_CLAMP = 33071, FILTER_LINEAR = 9729, FILTER_LINEAR_MIPMAP_LINEAR = 9987 };

typedef struct {
    float *pos, *nrm, *uv;
    uint32_t *idx;
    int n_verts, n_tris;
} geometry;

/* Accessors of one uploaded geometry. */
typedef struct {
    int position, normal, texcoord, indices;
} geometry_accessors;

typedef struct {
    glb_t g;
    int mat_glass, mat_frame, mat_lamp, mat_door;
    geometry_accessors box, quad, frame;
    int mesh_glass, mesh_frame;
    const museum_light *light;
    long long static_tris; /* per frame, besides the vessels */
    int static_calls;
} builder;

double museum_case_light(const layout_exhibit *e)
{
    return MUSEUM_CASE_LIGHT_PER_M2 * e->case_height * e->case_height;
}

/* ------------------------------------------------------------------ geometry */

static int upload(builder *b, const geometry *geo, geometry_accessors *acc)
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int i = 0; i < geo->n_verts; i++)
        for (int k = 0; k < 3; k++) {
            lo[k] = fmin(lo[k], geo->pos[3 * i + k]);
            hi[k] = fmax(hi[k], geo->pos[3 * i + k]);
        }
    size_t nv = (size_t)geo->n_verts;
    int vp = glb_add_view(&b->g, geo->pos, nv * 3 * sizeof(float), GLB_ARRAY_BUFFER);
    int vn = glb_add_view(&b->g, geo->nrm, nv * 3 * sizeof(float), GLB_ARRAY_BUFFER);
    int vt = glb_add_view(&b->g, geo->uv, nv * 2 * sizeof(float), GLB_ARRAY_BUFFER);
    int vi = glb_add_view(&b->g, geo->idx, (size_t)geo->n_tris * 3 * sizeof(uint32_t), GLB_ELEMENT_ARRAY_BUFFER);
    if (vp < 0 || vn < 0 || vt < 0 || vi < 0)
        return -1;
    acc->position = glb_add_accessor(&b->g, vp, GLB_FLOAT, geo->n_verts, "VEC3", lo, hi);
    acc->normal = glb_add_accessor(&b->g, vn, GLB_FLOAT, geo->n_verts, "VEC3", NULL, NULL);
    acc->texcoord = glb_add_accessor(&b->g, vt, GLB_FLOAT, geo->n_verts, "VEC2", NULL, NULL);
    acc->indices = glb_add_accessor(&b->g, vi, GLB_UNSIGNED_INT, geo->n_tris * 3, "SCALAR", NULL, NULL);
    return acc->position < 0 || acc->normal < 0 || acc->texcoord < 0 || acc->indices < 0 ? -1 : 0;
}

/* The vessels' levels with KHR_mesh_quantization: positions as 16-bit
 * integers q with p = offset + scale q (the level's node carries offset and
 * scale, uniform so normals stay normal), normals as normalized bytes,
 * texture coordinates as normalized 16-bit, indices 16-bit when they fit:
 * 16 bytes a vertex instead of 32, and a third of the indices' bytes. A
 * vertex moves by at most sqrt(3)/2 scale, scale = half the level's largest
 * extent / 32767 (9 micrometres on a 60 cm vessel). */
enum { Q_POSITION_MAX = 32767, Q_NORMAL_MAX = 127, Q_UV_MAX = 65535 };

typedef struct {
    int16_t p[4]; /* x, y, z, padding: 8-byte stride */
} q_position;

static double clampd(double v, double lo, double hi) { return v < lo ? lo : v > hi ? hi : v; }

static int upload_quantized(builder *b, const geometry *geo, geometry_accessors *acc, vec3 *offset, double *scale)
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY}, half = 0;
    for (int i = 0; i < geo->n_verts; i++)
        for (int k = 0; k < 3; k++) {
            lo[k] = fmin(lo[k], geo->pos[3 * i + k]);
            hi[k] = fmax(hi[k], geo->pos[3 * i + k]);
        }
    double mid[3];
    for (int k = 0; k < 3; k++)
        mid[k] = 0.5 * (lo[k] + hi[k]), half = fmax(half, 0.5 * (hi[k] - lo[k]));
    *offset = v3(mid[0], mid[1], mid[2]);
    *scale = half > 0 ? half / Q_POSITION_MAX : 1.0;
    size_t nv = (size_t)geo->n_verts, ni = (size_t)geo->n_tris * 3;
    int small = geo->n_verts <= 65535; /* 65535 itself is the restart index some APIs reserve */
    q_position *qp = malloc(nv * sizeof *qp);
    int8_t *qn = malloc(nv * 4);
    uint16_t *qt = malloc(nv * 2 * sizeof *qt);
    void *qi = malloc(ni * (small ? sizeof(uint16_t) : sizeof(uint32_t)));
    int rc = -1;
    if (!qp || !qn || !qt || !qi)
        goto done;
    double qlo[3] = {Q_POSITION_MAX, Q_POSITION_MAX, Q_POSITION_MAX}, qhi[3] = {-Q_POSITION_MAX, -Q_POSITION_MAX, -Q_POSITION_MAX};
    for (size_t i = 0; i < nv; i++) {
        for (int k = 0; k < 3; k++) {
            double q = lround(clampd((geo->pos[3 * i + k] - mid[k]) / *scale, -Q_POSITION_MAX, Q_POSITION_MAX));
            qp[i].p[k] = (int16_t)q;
            qlo[k] = fmin(qlo[k], q), qhi[k] = fmax(qhi[k], q);
            qn[4 * i + k] = (int8_t)lround(clampd(geo->nrm[3 * i + k], -1, 1) * Q_NORMAL_MAX);
        }
        qp[i].p[3] = 0, qn[4 * i + 3] = 0;
        for (int k = 0; k < 2; k++)
            qt[2 * i + k] = (uint16_t)lround(clampd(geo->uv[2 * i + k], 0, 1) * Q_UV_MAX);
    }
    for (size_t i = 0; i < ni; i++) {
        if (small)
            ((uint16_t *)qi)[i] = (uint16_t)geo->idx[i];
        else
            ((uint32_t *)qi)[i] = geo->idx[i];
    }
    int vp = glb_add_strided_view(&b->g, qp, nv * sizeof *qp, GLB_ARRAY_BUFFER, (int)sizeof *qp);
    int vn = glb_add_strided_view(&b->g, qn, nv * 4, GLB_ARRAY_BUFFER, 4);
    int vt = glb_add_view(&b->g, qt, nv * 2 * sizeof *qt, GLB_ARRAY_BUFFER);
    int vi = glb_add_view(&b->g, qi, ni * (small ? sizeof(uint16_t) : sizeof(uint32_t)), GLB_ELEMENT_ARRAY_BUFFER);
    if (vp < 0 || vn < 0 || vt < 0 || vi < 0)
        goto done;
    acc->position = glb_add_accessor(&b->g, vp, GLB_SHORT, geo->n_verts, "VEC3", qlo, qhi);
    acc->normal = glb_add_accessor(&b->g, vn, GLB_BYTE, geo->n_verts, "VEC3", NULL, NULL);
    acc->texcoord = glb_add_accessor(&b->g, vt, GLB_UNSIGNED_SHORT, geo->n_verts, "VEC2", NULL, NULL);
    acc->indices = glb_add_accessor(&b->g, vi, small ? GLB_UNSIGNED_SHORT : GLB_UNSIGNED_INT, (int)ni, "SCALAR", NULL, NULL);
    rc = acc->position < 0 || acc->normal < 0 || acc->texcoord < 0 || acc->indices < 0 ||
                 glb_set_normalized(&b->g, acc->normal) != 0 || glb_set_normalized(&b->g, acc->texcoord) != 0
             ? -1
             : 0;
done:
    free(qp), free(qn), free(qt), free(qi);
    return rc;
}

static int add_mesh(builder *b, const char *name, const geometry_accessors *acc, int material)
{
    json_t *prim = json_pack("{s:{s:i, s:i, s:i}, s:i, s:i}", "attributes", "POSITION", acc->position, "NORMAL",
                             acc->normal, "TEXCOORD_0", acc->texcoord, "indices", acc->indices, "material", material);
    return glb_append(&b->g, "meshes", json_pack("{s:s, s:[o]}", "name", name, "primitives", prim));
}

/* Axis-aligned quads (room_surfaces.h), each given by a corner and two edge
 * vectors whose cross product is its normal; UVs span [0,1]^2 per quad (v
 * down the image). */
static int quads_geometry(const quad_spec *q, int n, geometry *geo)
{
    geo->n_verts = 4 * n;
    geo->n_tris = 2 * n;
    geo->pos = malloc((size_t)geo->n_verts * 3 * sizeof(float));
    geo->nrm = malloc((size_t)geo->n_verts * 3 * sizeof(float));
    geo->uv = malloc((size_t)geo->n_verts * 2 * sizeof(float));
    geo->idx = malloc((size_t)geo->n_tris * 3 * sizeof(uint32_t));
    if (!geo->pos || !geo->nrm || !geo->uv || !geo->idx)
        return -1;
    static const double su[4] = {0, 1, 1, 0}, sv[4] = {0, 0, 1, 1};
    for (int k = 0; k < n; k++) {
        vec3 nrm = v3_norm(v3_cross(q[k].du, q[k].dv));
        for (int c = 0; c < 4; c++) {
            vec3 p = v3_add(q[k].corner, v3_add(v3_scale(q[k].du, su[c]), v3_scale(q[k].dv, sv[c])));
            float *pp = geo->pos + 3 * (4 * k + c), *nn = geo->nrm + 3 * (4 * k + c), *tt = geo->uv + 2 * (4 * k + c);
            pp[0] = (float)p.x, pp[1] = (float)p.y, pp[2] = (float)p.z;
            nn[0] = (float)nrm.x, nn[1] = (float)nrm.y, nn[2] = (float)nrm.z;
            tt[0] = (float)su[c], tt[1] = (float)(1.0 - sv[c]);
        }
        static const uint32_t tri[6] = {0, 1, 2, 0, 2, 3};
        for (int t = 0; t < 6; t++)
            geo->idx[6 * k + t] = (uint32_t)(4 * k) + tri[t];
    }
    return 0;
}

static void geometry_free(geometry *geo)
{
    free(geo->pos), free(geo->nrm), free(geo->uv), free(geo->idx);
    memset(geo, 0, sizeof *geo);
}

static int upload_quads(builder *b, const quad_spec *q, int n, geometry_accessors *acc)
{
    geometry geo = {0};
    int rc = quads_geometry(q, n, &geo) == 0 ? upload(b, &geo, acc) : -1;
    geometry_free(&geo);
    return rc;
}

/* Quads whose UVs are their tiles of lightmap m, moved by -origin. */
static int upload_lightmapped(builder *b, const quad_spec *q, int n, const lightmap_layout *m, vec3 origin,
                              geometry_accessors *acc)
{
    geometry geo = {0};
    int rc = quads_geometry(q, n, &geo);
    for (int i = 0; rc == 0 && i < geo.n_verts; i++) {
        double u, v;
        lightmap_uv(m, i / 4, geo.uv[2 * i], 1.0 - geo.uv[2 * i + 1], &u, &v);
        geo.uv[2 * i] = (float)u, geo.uv[2 * i + 1] = (float)v;
        for (int k = 0; k < 3; k++)
            geo.pos[3 * i + k] -= (float)(k == 0 ? origin.x : k == 1 ? origin.y : origin.z);
    }
    rc = rc == 0 ? upload(b, &geo, acc) : -1;
    geometry_free(&geo);
    return rc;
}

/* The unit box x, z in [-0.5, 0.5], y in [0, 1] without its bottom face,
 * normals outward: pedestals and glass cases, scaled by their nodes. */
static int upload_box(builder *b)
{
    const quad_spec box[5] = {
        {{-0.5, 0, 0.5}, {1, 0, 0}, {0, 1, 0}},   /* front, +z */
        {{0.5, 0, -0.5}, {-1, 0, 0}, {0, 1, 0}},  /* back, -z */
        {{0.5, 0, 0.5}, {0, 0, -1}, {0, 1, 0}},   /* right, +x */
        {{-0.5, 0, -0.5}, {0, 0, 1}, {0, 1, 0}},  /* left, -x */
        {{-0.5, 1, 0.5}, {1, 0, 0}, {0, 0, -1}},  /* top, +y */
    };
    return upload_quads(b, box, 5, &b->box);
}

/* The six faces of the box [lo, hi] as quads, normals outward. */
static void box_quads(vec3 lo, vec3 hi, quad_spec *q)
{
    vec3 d = v3_sub(hi, lo);
    q[0] = (quad_spec){{lo.x, lo.y, hi.z}, {d.x, 0, 0}, {0, d.y, 0}};  /* +z */
    q[1] = (quad_spec){{hi.x, lo.y, lo.z}, {-d.x, 0, 0}, {0, d.y, 0}}; /* -z */
    q[2] = (quad_spec){{hi.x, lo.y, hi.z}, {0, 0, -d.z}, {0, d.y, 0}}; /* +x */
    q[3] = (quad_spec){{lo.x, lo.y, lo.z}, {0, 0, d.z}, {0, d.y, 0}};  /* -x */
    q[4] = (quad_spec){{lo.x, hi.y, hi.z}, {d.x, 0, 0}, {0, 0, -d.z}}; /* +y */
    q[5] = (quad_spec){{lo.x, lo.y, lo.z}, {d.x, 0, 0}, {0, 0, d.z}};  /* -y */
}

/* The twelve edges of the unit case box as bars FRAME_BAR thick (of the
 * box's side, so about 5 mm on a case): the metal frame that makes the
 * glass read as a case. */
#define FRAME_BAR 0.012
static int upload_frame(builder *b)
{
    quad_spec q[12 * 6];
    const double t = FRAME_BAR / 2;
    int n = 0;
    for (int a = -1; a <= 1; a += 2)
        for (int c = -1; c <= 1; c += 2) {
            double y = a < 0 ? 0 : 1, s = 0.5 * c, u = 0.5 * a;
            box_quads(v3(-0.5, y - t, s - t), v3(0.5, y + t, s + t), q + 6 * n++); /* along x */
            box_quads(v3(s - t, y - t, -0.5), v3(s + t, y + t, 0.5), q + 6 * n++); /* along z */
            box_quads(v3(u - t, 0, s - t), v3(u + t, 1, s + t), q + 6 * n++);     /* upright */
        }
    return upload_quads(b, q, 6 * n, &b->frame);
}

/* The unit quad [-0.5, 0.5]^2 in z = 0 facing +z: labels. */
static int upload_label_quad(builder *b)
{
    const quad_spec q = {{-0.5, -0.5, 0}, {1, 0, 0}, {0, 1, 0}};
    return upload_quads(b, &q, 1, &b->quad);
}

/* ------------------------------------------------------------------ materials */

static json_t *pbr(double r, double g, double bl, double roughness)
{
    return json_pack("{s:[f,f,f,f], s:f, s:f}", "baseColorFactor", r, g, bl, 1.0, "metallicFactor", 0.0,
                     "roughnessFactor", roughness);
}

static int add_plain_material(builder *b, const char *name, double r, double g, double bl, double roughness)
{
    return glb_append(&b->g, "materials", json_pack("{s:s, s:o}", "name", name, "pbrMetallicRoughness",
                                                    pbr(r, g, bl, roughness)));
}

/* An embedded image (PNG or JPEG bytes, mime its type) as a texture;
 * returns the texture index. */
static int add_texture(builder *b, const char *name, const uint8_t *bytes, size_t len, const char *mime)
{
    if (!json_object_get(b->g.doc, "samplers"))
        glb_append(&b->g, "samplers", json_pack("{s:i, s:i, s:i, s:i}", "magFilter", FILTER_LINEAR, "minFilter",
                                                FILTER_LINEAR_MIPMAP_LINEAR, "wrapS", SAMPLER_CLAMP, "wrapT",
                                                SAMPLER_CLAMP));
    int view = glb_add_view(&b->g, bytes, len, 0);
    if (view < 0)
        return -1;
    int image = glb_append(&b->g, "images", json_pack("{s:s, s:i, s:s}", "name", name, "bufferView", view,
                                                      "mimeType", mime));
    return glb_append(&b->g, "textures", json_pack("{s:s, s:i, s:i}", "name", name, "sampler", 0, "source", image));
}

static int add_textured_material(builder *b, const char *name, int texture, double roughness, int clearcoat)
{
    json_t *m = json_pack("{s:s, s:{s:{s:i}, s:f, s:f}}", "name", name, "pbrMetallicRoughness", "baseColorTexture",
                          "index", texture, "metallicFactor", 0.0, "roughnessFactor", roughness);
    /* A glaze is seen from inside too: an open bowl from above shows its
     * inner wall, the far side's back faces. */
    if (m && clearcoat)
        json_object_set_new(m, "doubleSided", json_true());
    /* museum.xml's `plastic`: a diffuse body under one smooth dielectric
     * coat, so the clear coat is the glaze's only specular layer (the base
     * layer's own is off: KHR_materials_specular). */
    if (m && clearcoat)
        json_object_set_new(m, "extensions",
                            json_pack("{s:{s:f, s:f}, s:{s:f}}", "KHR_materials_clearcoat", "clearcoatFactor", 1.0,
                                      "clearcoatRoughnessFactor", 0.05, "KHR_materials_specular", "specularFactor",
                                      0.0));
    return glb_append(&b->g, "materials", m);
}

/* A surface whose light is baked (museum_light.h): its lightmap, the
 * render's code values, drawn as it is (KHR_materials_unlit). */
static int add_baked_material(builder *b, const char *name, const museum_file_bytes *jpeg)
{
    int tex = add_texture(b, name, jpeg->bytes, jpeg->len, "image/jpeg");
    if (tex < 0)
        return -1;
    return glb_append(&b->g, "materials",
                      json_pack("{s:s, s:{s:{s:i}, s:f, s:f}, s:{s:{}}}", "name", name, "pbrMetallicRoughness",
                                "baseColorTexture", "index", tex, "metallicFactor", 0.0, "roughnessFactor", 1.0,
                                "extensions", "KHR_materials_unlit"));
}

static int add_materials(builder *b)
{
    b->mat_frame = add_plain_material(b, "Case frame", 0.10, 0.10, 0.10, 0.35);
    /* The lamps glow with the lights' colour (emission only: the point lights light the room). */
    b->mat_lamp = glb_append(&b->g, "materials",
                             json_pack("{s:s, s:o, s:[f,f,f]}", "name", "Lamp", "pbrMetallicRoughness",
                                       pbr(1, 1, 1, 0.9), "emissiveFactor", MUSEUM_LIGHT_COLOR_R, MUSEUM_LIGHT_COLOR_G,
                                       MUSEUM_LIGHT_COLOR_B));
    json_t *glass = json_pack("{s:s, s:o, s:{s:{s:f}, s:{s:f}}}", "name", "Glass", "pbrMetallicRoughness",
                              pbr(1, 1, 1, 0.0), "extensions", "KHR_materials_transmission", "transmissionFactor",
                              1.0, "KHR_materials_ior", "ior", 1.5);
    b->mat_glass = glb_append(&b->g, "materials", glass);
    b->mat_door = add_plain_material(b, "Door", 0.30, 0.18, 0.10, 0.5);
    return b->mat_glass < 0 || b->mat_frame < 0 || b->mat_lamp < 0 || b->mat_door < 0 ? -1 : 0;
}

/* ------------------------------------------------------------------ nodes */

static json_t *vec_json(vec3 v) { return json_pack("[f,f,f]", v.x, v.y, v.z); }

static json_t *node(const char *name, vec3 translation)
{
    return json_pack("{s:s, s:o}", "name", name, "translation", vec_json(translation));
}

static int add_child(json_t *parent, int child)
{
    if (child < 0)
        return -1;
    json_t *children = json_object_get(parent, "children");
    if (!children) {
        children = json_array();
        json_object_set_new(parent, "children", children);
    }
    return json_array_append_new(children, json_integer(child));
}

static int add_light(builder *b, const char *name, double intensity)
{
    json_t *ext = json_object_get(b->g.doc, "extensions");
    if (!ext) {
        ext = json_pack("{s:{s:[]}}", "KHR_lights_punctual", "lights");
        json_object_set_new(b->g.doc, "extensions", ext);
    }
    json_t *lights = json_object_get(json_object_get(ext, "KHR_lights_punctual"), "lights");
    json_array_append_new(lights, json_pack("{s:s, s:s, s:[f,f,f], s:f}", "name", name, "type", "point", "color",
                                            MUSEUM_LIGHT_COLOR_R, MUSEUM_LIGHT_COLOR_G, MUSEUM_LIGHT_COLOR_B,
                                            "intensity", intensity));
    return (int)json_array_size(lights) - 1;
}

static int light_node(builder *b, const char *name, vec3 at, double intensity)
{
    int light = add_light(b, name, intensity);
    json_t *n = node(name, at);
    json_object_set_new(n, "extensions", json_pack("{s:{s:i}}", "KHR_lights_punctual", "light", light));
    return glb_append(&b->g, "nodes", n);
}

/* A unit-quaternion [x, y, z, w] of the rotation whose columns are the
 * camera's right, up and back (glTF cameras look down -z). */
static json_t *look_rotation(vec3 from, vec3 to)
{
    vec3 back = v3_norm(v3_sub(from, to));
    vec3 right = v3_norm(v3_cross(v3(0, 1, 0), back));
    vec3 up = v3_cross(back, right);
    double m[3][3] = {{right.x, up.x, back.x}, {right.y, up.y, back.y}, {right.z, up.z, back.z}};
    double q[4], tr = m[0][0] + m[1][1] + m[2][2];
    if (tr > 0) {
        double s = 2.0 * sqrt(tr + 1.0);
        q[3] = 0.25 * s, q[0] = (m[2][1] - m[1][2]) / s, q[1] = (m[0][2] - m[2][0]) / s, q[2] = (m[1][0] - m[0][1]) / s;
    } else if (m[0][0] > m[1][1] && m[0][0] > m[2][2]) {
        double s = 2.0 * sqrt(1.0 + m[0][0] - m[1][1] - m[2][2]);
        q[3] = (m[2][1] - m[1][2]) / s, q[0] = 0.25 * s, q[1] = (m[0][1] + m[1][0]) / s, q[2] = (m[0][2] + m[2][0]) / s;
    } else if (m[1][1] > m[2][2]) {
        double s = 2.0 * sqrt(1.0 + m[1][1] - m[0][0] - m[2][2]);
        q[3] = (m[0][2] - m[2][0]) / s, q[0] = (m[0][1] + m[1][0]) / s, q[1] = 0.25 * s, q[2] = (m[1][2] + m[2][1]) / s;
    } else {
        double s = 2.0 * sqrt(1.0 + m[2][2] - m[0][0] - m[1][1]);
        q[3] = (m[1][0] - m[0][1]) / s, q[0] = (m[0][2] + m[2][0]) / s, q[1] = (m[1][2] + m[2][1]) / s, q[2] = 0.25 * s;
    }
    double len = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    return json_pack("[f,f,f,f]", q[0] / len, q[1] / len, q[2] / len, q[3] / len);
}

static int camera_node(builder *b, const layout_t *l)
{
    int cam = glb_append(&b->g, "cameras",
                         json_pack("{s:s, s:s, s:{s:f, s:f, s:f, s:f}}", "name", "Entrance camera", "type",
                                   "perspective", "perspective", "yfov", l->camera_yfov_deg * M_PI / 180.0,
                                   "aspectRatio", l->camera_aspect, "znear", 0.05, "zfar", 500.0));
    json_t *n = node("Entrance camera", l->camera_position);
    json_object_set_new(n, "rotation", look_rotation(l->camera_position, l->camera_target));
    json_object_set_new(n, "camera", json_integer(cam));
    return glb_append(&b->g, "nodes", n);
}

static int mesh_node(builder *b, const char *name, int mesh, vec3 at, vec3 scale)
{
    json_t *n = node(name, at);
    json_object_set_new(n, "mesh", json_integer(mesh));
    json_object_set_new(n, "scale", vec_json(scale));
    return glb_append(&b->g, "nodes", n);
}

/* Floor, ceiling and the four walls, each its own mesh under its
 * lightmap; returns -1 or 0 and adds their nodes to the root. */
static int room_nodes(builder *b, const layout_t *l, json_t *root)
{
    quad_spec q[ROOM_SURFACES];
    room_surfaces(l, q);
    for (int k = 0; k < ROOM_SURFACES; k++) {
        geometry_accessors acc;
        const char *name = room_surface_names[k];
        int mat = add_baked_material(b, name, &b->light->room[k]);
        if (mat < 0 || upload_lightmapped(b, &q[k], 1, &b->light->room_layout[k], v3(0, 0, 0), &acc) != 0)
            return -1;
        int mesh = add_mesh(b, name, &acc, mat);
        if (mesh < 0 || add_child(root, mesh_node(b, name, mesh, v3(0, 0, 0), v3(1, 1, 1))) != 0)
            return -1;
        b->static_tris += 2;
        b->static_calls++;
    }
    return 0;
}

/* The visible light fixtures, as one mesh: under each ceiling light's point
 * a glowing shade LAMP_SIDE square, and a rod up to the ceiling. */
#define LAMP_SIDE 0.3
#define LAMP_THICK 0.04
#define ROD_SIDE 0.012
static int lamp_nodes(builder *b, const layout_t *l, json_t *root)
{
    int n = l->n_ceiling_lights;
    quad_spec *shades = malloc((size_t)(n > 0 ? n : 1) * 6 * sizeof *shades);
    quad_spec *rods = malloc((size_t)(n > 0 ? n : 1) * 6 * sizeof *rods);
    int rc = shades && rods ? 0 : -1;
    for (int k = 0; k < n && rc == 0; k++) {
        vec3 p = l->ceiling_lights[k];
        /* The shade sits just above the light, so the point stays in the open. */
        box_quads(v3(p.x - LAMP_SIDE / 2, p.y + 0.01, p.z - LAMP_SIDE / 2),
                  v3(p.x + LAMP_SIDE / 2, p.y + 0.01 + LAMP_THICK, p.z + LAMP_SIDE / 2), shades + 6 * k);
        box_quads(v3(p.x - ROD_SIDE / 2, p.y + 0.01 + LAMP_THICK, p.z - ROD_SIDE / 2),
                  v3(p.x + ROD_SIDE / 2, l->height, p.z + ROD_SIDE / 2), rods + 6 * k);
    }
    const quad_spec *parts[2] = {shades, rods};
    const int materials[2] = {b->mat_lamp, b->mat_frame};
    const char *names[2] = {"Lamps", "Lamp rods"};
    for (int i = 0; i < 2 && rc == 0 && n > 0; i++) {
        geometry_accessors acc;
        int mesh = upload_quads(b, parts[i], 6 * n, &acc) == 0 ? add_mesh(b, names[i], &acc, materials[i]) : -1;
        rc = mesh < 0 || add_child(root, mesh_node(b, names[i], mesh, v3(0, 0, 0), v3(1, 1, 1))) != 0 ? -1 : 0;
        b->static_tris += 12 * n;
        b->static_calls++;
    }
    free(shades);
    free(rods);
    return rc;
}

/* The vessel node and one child per level; returns the vessel node. */
static int vessel_node(builder *b, const museum_exhibit *e, vec3 at, int material)
{
    char name[400];
    json_t *lods = json_array();
    json_t *vn = node("", at);
    snprintf(name, sizeof name, "Vessel: %s", e->title);
    json_object_set_new(vn, "name", json_string(name));
    for (int k = 0; k < e->n_lods; k++) {
        const lod_level *l = &e->lods[k];
        geometry geo = {l->mesh.pos, l->mesh.nrm, NULL, l->mesh.tri, l->mesh.n_verts, l->mesh.n_tris};
        /* glTF's v runs down the image; the mesh's v runs up from the base. */
        float *uv = malloc((size_t)l->mesh.n_verts * 2 * sizeof(float));
        if (!uv)
            return -1;
        for (int i = 0; i < l->mesh.n_verts; i++)
            uv[2 * i] = l->mesh.uv[2 * i], uv[2 * i + 1] = 1.0f - l->mesh.uv[2 * i + 1];
        geo.uv = uv;
        geometry_accessors acc;
        vec3 offset;
        double scale;
        int rc = upload_quantized(b, &geo, &acc, &offset, &scale);
        free(uv);
        snprintf(name, sizeof name, "%s, LOD %d (%d segments)", e->title, k, l->segments);
        int mesh = rc == 0 ? add_mesh(b, name, &acc, material) : -1;
        json_t *child = json_pack("{s:s, s:i, s:o, s:[f,f,f], s:{s:f, s:i, s:f}}", "name", name, "mesh", mesh,
                                  "translation", vec_json(offset), "scale", scale, scale, scale, "extras",
                                  "lod_distance", l->distance, "segments", l->segments, "error_m", l->error);
        if (mesh < 0 || add_child(vn, glb_append(&b->g, "nodes", child)) != 0)
            return -1;
        json_array_append_new(lods, json_pack("{s:i, s:f, s:i}", "segments", l->segments, "distance", l->distance,
                                              "triangles", l->mesh.n_tris));
    }
    json_object_set_new(vn, "extras", json_pack("{s:o}", "lod", lods));
    return glb_append(&b->g, "nodes", vn);
}

static json_t *exhibit_extras(const museum_exhibit *e, int index)
{
    char profile[160], probe[160];
    snprintf(profile, sizeof profile, "vessels/%s/profile.json", e->slug);
    snprintf(probe, sizeof probe, "vessels/%s/probe.hdr", e->slug);
    char size[128];
    vessel_size_line(e->height_cm_given, e->diameter_cm_given, size, sizeof size);
    json_t *x = json_pack("{s:i, s:s, s:f, s:s, s:s, s:s, s:s}", "index", index, "title", e->title, "height_cm",
                          100.0 * e->height_m, "size", size, "size_from", vessel_size_source_name(e->size_source),
                          "photo", e->photo, "profile", profile);
    json_object_set_new(x, "probe", json_string(probe));
    if (e->below_gate)
        json_object_set_new(x, "note", json_string(MUSEUM_BELOW_GATE_NOTE));
    if (e->date)
        json_object_set_new(x, "date", json_string(e->date));
    if (e->description)
        json_object_set_new(x, "description", json_string(e->description));
    return x;
}

/* A plate (the unit quad, scaled) with its PNG, a child of parent at `at`. */
static int plate_node(builder *b, json_t *parent, const char *name, const uint8_t *png, size_t len, vec3 at,
                      double width, double height)
{
    int tex = add_texture(b, name, png, len, "image/png");
    int mat = tex < 0 ? -1 : add_textured_material(b, name, tex, 0.9, 0);
    int mesh = mat < 0 ? -1 : add_mesh(b, name, &b->quad, mat);
    return mesh < 0 ? -1 : add_child(parent, mesh_node(b, name, mesh, at, v3(width, height, 1)));
}

static int exhibit_node(builder *b, const museum_exhibit *e, const layout_exhibit *le, int index)
{
    char name[400];
    snprintf(name, sizeof name, "Exhibit: %s", e->title);
    json_t *en = node(name, le->centre);
    json_object_set_new(en, "extras", exhibit_extras(e, index));
    vec3 up = v3(0, le->pedestal_height, 0);
    snprintf(name, sizeof name, "Pedestal: %s", e->title);
    quad_spec faces[PEDESTAL_FACES];
    pedestal_faces(le, faces);
    geometry_accessors acc;
    int pmat = add_baked_material(b, name, &b->light->pedestal[index]);
    int pmesh = pmat < 0 || upload_lightmapped(b, faces, PEDESTAL_FACES, &b->light->pedestal_layout[index],
                                               le->centre, &acc) != 0
                    ? -1
                    : add_mesh(b, name, &acc, pmat);
    int rc = pmesh < 0 ? -1 : add_child(en, mesh_node(b, name, pmesh, v3(0, 0, 0), v3(1, 1, 1)));
    snprintf(name, sizeof name, "Glass case: %s", e->title);
    rc |= add_child(en, mesh_node(b, name, b->mesh_glass, up, v3(le->width, le->case_height, le->width)));
    snprintf(name, sizeof name, "Case frame: %s", e->title);
    rc |= add_child(en, mesh_node(b, name, b->mesh_frame, up, v3(le->width, le->case_height, le->width)));

    snprintf(name, sizeof name, "Glaze: %s", e->title);
    int tex = add_texture(b, name, e->texture_jpg, e->texture_len, "image/jpeg");
    int glaze = tex < 0 ? -1 : add_textured_material(b, name, tex, 0.45, 1);
    rc |= glaze < 0 ? -1 : add_child(en, vessel_node(b, e, up, glaze));

    snprintf(name, sizeof name, "Label: %s", e->title);
    rc |= plate_node(b, en, name, e->label_png, e->label_len, v3_sub(le->label_centre, le->centre),
                     le->label_width, le->label_height);
    if (e->sign_png) {
        snprintf(name, sizeof name, "Sign: %s", e->title);
        rc |= plate_node(b, en, name, e->sign_png, e->sign_len, v3_sub(le->sign_centre, le->centre),
                         le->sign_width, le->sign_height);
    }
    snprintf(name, sizeof name, "Case light: %s", e->title);
    rc |= add_child(en, light_node(b, name, v3_sub(le->light, le->centre), museum_case_light(le)));
    return rc != 0 ? -1 : glb_append(&b->g, "nodes", en);
}

/* ------------------------------------------------------------------ figures */

/* The level three.js's LOD shows at distance d: the last one whose distance is not beyond it. */
static int level_at(const museum_exhibit *e, double d)
{
    int k = 0;
    while (k + 1 < e->n_lods && e->lods[k + 1].distance <= d)
        k++;
    return k;
}

static void figures(const builder *b, const layout_t *l, const museum_exhibit *ex, int n, museum_report *rep)
{
    /* Per exhibit: pedestal and case (5 quads each), the case's frame (12
     * bars of 6 quads), label (1 quad), and the title sign (1 quad) when it has one. */
    long long per_exhibit = 10 + 10 + 12 * 6 * 2 + 2, signs = 0;
    for (int i = 0; i < n; i++)
        signs += ex[i].sign_png != NULL;
    rep->triangles_full = rep->triangles_entrance = rep->triangles_coarsest =
        b->static_tris + n * per_exhibit + 2 * signs;
    for (int i = 0; i < n; i++) {
        double d = v3_len(v3_sub(l->camera_position, l->exhibits[i].vessel_base));
        rep->triangles_full += ex[i].lods[0].mesh.n_tris;
        rep->triangles_entrance += ex[i].lods[level_at(&ex[i], d)].mesh.n_tris;
        rep->triangles_coarsest += ex[i].lods[ex[i].n_lods - 1].mesh.n_tris;
    }
    rep->draw_calls = b->static_calls + 5 * n + (int)signs;
}

/* The entrance (layout.h): a wooden leaf in the middle of the entrance wall
 * (+z), behind the entrance camera, standing DOOR_DEPTH proud of the wall
 * in a casing of bars DOOR_CASING wide and twice as deep, with a dark
 * handle; the door as one mesh, the handle as another. */
#define DOOR_DEPTH 0.03
#define DOOR_CASING 0.08
static int door_nodes(builder *b, const layout_t *l, json_t *root)
{
    const double z = 0.5 * l->depth, w = 0.5 * LAYOUT_DOOR_WIDTH, h = LAYOUT_DOOR_HEIGHT, c = DOOR_CASING;
    quad_spec door[4 * 6], handle[6];
    box_quads(v3(-w, 0, z - DOOR_DEPTH), v3(w, h, z), door);                      /* leaf */
    box_quads(v3(-w - c, 0, z - 2 * DOOR_DEPTH), v3(-w, h + c, z), door + 6);    /* left jamb */
    box_quads(v3(w, 0, z - 2 * DOOR_DEPTH), v3(w + c, h + c, z), door + 12);     /* right jamb */
    box_quads(v3(-w, h, z - 2 * DOOR_DEPTH), v3(w, h + c, z), door + 18);        /* head */
    box_quads(v3(w - 0.12, 0.95, z - DOOR_DEPTH - 0.05), v3(w - 0.1, 1.1, z - DOOR_DEPTH), handle);
    const quad_spec *parts[2] = {door, handle};
    const int n_quads[2] = {4 * 6, 6}, materials[2] = {b->mat_door, b->mat_frame};
    const char *names[2] = {"Entrance door", "Door handle"};
    for (int i = 0; i < 2; i++) {
        geometry_accessors acc;
        int mesh = upload_quads(b, parts[i], n_quads[i], &acc) == 0 ? add_mesh(b, names[i], &acc, materials[i]) : -1;
        if (mesh < 0 || add_child(root, mesh_node(b, names[i], mesh, v3(0, 0, 0), v3(1, 1, 1))) != 0)
            return -1;
        b->static_tris += 2 * n_quads[i];
        b->static_calls++;
    }
    return 0;
}

static int build(builder *b, const char *title, const layout_t *l, const museum_exhibit *ex, int n)
{
    static const char *const extensions[] = {"KHR_materials_clearcoat", "KHR_materials_transmission",
                                             "KHR_materials_ior", "KHR_lights_punctual", "KHR_materials_unlit",
                                             "KHR_materials_specular"};
    for (size_t k = 0; k < sizeof extensions / sizeof *extensions; k++)
        if (glb_use_extension(&b->g, extensions[k]) != 0)
            return -1;
    if (glb_require_extension(&b->g, "KHR_mesh_quantization") != 0)
        return -1;
    if (add_materials(b) != 0 || upload_box(b) != 0 || upload_label_quad(b) != 0 || upload_frame(b) != 0)
        return -1;
    b->mesh_frame = add_mesh(b, "Case frame", &b->frame, b->mat_frame);
    b->mesh_glass = add_mesh(b, "Glass case", &b->box, b->mat_glass);
    char name[400];
    snprintf(name, sizeof name, "Museum: %s", title);
    json_t *root = node(name, v3(0, 0, 0));
    json_object_set_new(root, "extras",
                        json_pack("{s:{s:s, s:i, s:[f,f,f], s:f, s:s}}", "celadon_museum", "title", title, "vessels", n,
                                  "room", l->width, l->depth, l->height, "aisle", LAYOUT_AISLE, "probe",
                                  "probe.hdr"));
    int rc = room_nodes(b, l, root);
    rc |= lamp_nodes(b, l, root);
    rc |= door_nodes(b, l, root);
    rc |= add_child(root, camera_node(b, l));
    for (int k = 0; k < l->n_ceiling_lights && rc == 0; k++) {
        snprintf(name, sizeof name, "Ceiling light %d", k + 1);
        rc |= add_child(root, light_node(b, name, l->ceiling_lights[k], MUSEUM_CEILING_LIGHT));
    }
    for (int i = 0; i < n && rc == 0; i++)
        rc |= add_child(root, exhibit_node(b, &ex[i], &l->exhibits[i], i));
    int root_index = rc == 0 ? glb_append(&b->g, "nodes", root) : -1;
    if (root_index < 0)
        return -1;
    json_object_set_new(b->g.doc, "scene", json_integer(0));
    return glb_append(&b->g, "scenes", json_pack("{s:s, s:[i]}", "name", title, "nodes", root_index)) < 0 ? -1 : 0;
}

int museum_gltf_write(const char *path, const char *title, const layout_t *layout, const museum_exhibit *ex,
                      int n, const museum_light *light, museum_report *rep, char *err, size_t errlen)
{
    builder b = {.light = light};
    if (glb_init(&b.g, "celadon museum") != 0 || build(&b, title, layout, ex, n) != 0) {
        glb_free(&b.g);
        snprintf(err, errlen, "cannot build museum.glb (out of memory?)");
        return -1;
    }
    figures(&b, layout, ex, n, rep);
    int rc = glb_write(&b.g, path, err, errlen);
    glb_free(&b.g);
    struct stat st;
    if (rc == 0 && stat(path, &st) == 0)
        rep->glb_bytes = (long long)st.st_size;
    return rc;
}
