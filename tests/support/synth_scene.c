/* Synthetic museum photographs: the compositor, the truth and the table of
 * named cases (see synth_scene.h). The layers themselves are in
 * synth_scene_layers.c. */
#include "synth_scene.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "synth_jpeg.h"
#include "synth_noise.h"
#include "synth_scene_layers.h"

/* ------------------------------------------------------------------ validation */

static int attachment_valid(const synth_attachment *a)
{
    if (a->kind == SYNTH_ATTACH_NONE)
        return 1;
    return (a->side == -1 || a->side == 1) && a->h0 >= 0 && a->h0 <= 1 && a->h1 >= 0 && a->h1 <= 1 && a->reach >= 0 &&
           a->thickness > 0;
}

static int params_valid(const synth_scene_params *p)
{
    if (p->width < 8 || p->height < 8 || (double)p->width * p->height > 1e8 || p->vessel_count < 0 ||
        p->vessel_count > 2 || p->noise < 0 || p->jpeg_quality < 0 || p->jpeg_quality > 100 || p->subrows < 0 ||
        (p->supersample != 0 && p->supersample < 8) || p->shadow.strength < 0 || p->shadow.strength > 1 ||
        p->contact_shadow < 0 || p->contact_shadow > 1 ||
        (p->backdrop.kind == SYNTH_BACKDROP_SWEEP && !(p->backdrop.softness > 0)) ||
        (p->backdrop.grain > 0 && !(p->backdrop.grain_px > 0)))
        return 0;
    for (int k = 0; k < p->vessel_count; k++)
        if (!synth_body_valid(&p->vessels[k].body))
            return 0;
    int has_parts = p->stand.kind != SYNTH_STAND_NONE || p->shadow.strength > 0 || p->contact_shadow > 0;
    for (int k = 0; k < SYNTH_SCENE_MAX_ATTACHMENTS; k++) {
        has_parts |= p->attachments[k].kind != SYNTH_ATTACH_NONE;
        if (!attachment_valid(&p->attachments[k]))
            return 0;
    }
    if (has_parts && p->vessel_count < 1)
        return 0;
    if (p->stand.kind != SYNTH_STAND_NONE &&
        (p->vessels[0].body.tilt_deg != 0 || !(p->stand.width > 0) || !(p->stand.height > 0) || p->stand.depth < 0))
        return 0;
    if (p->shadow.strength > 0 && (!(p->shadow.length > 0) || !(p->shadow.breadth > 0) ||
                                   (p->shadow.side != -1 && p->shadow.side != 1)))
        return 0;
    return 1;
}

/* ------------------------------------------------------------------ compositing */

/* A drawn layer: its weight per pixel (coverage; for a shadow, darkening)
 * and what the truth calls it (SYNTH_PART_KIND_COUNT: the subject's body). */
typedef struct {
    synth_part_kind kind;
    int side;     /* declared side, or 0: found from where it shows */
    int occludes; /* opaque: hides what lies under it */
    float *weight;
} layer;

enum { MAX_LAYERS = SYNTH_SCENE_MAX_PARTS + 1 };

typedef struct {
    int count;
    layer l[MAX_LAYERS];
} layer_stack;

static float *push(layer_stack *s, size_t pixels, synth_part_kind kind, int side, int occludes)
{
    float *w = calloc(pixels, sizeof *w);
    if (w)
        s->l[s->count++] = (layer){kind, side, occludes, w};
    return w;
}

static void free_layers(layer_stack *s)
{
    for (int k = 0; k < s->count; k++)
        free(s->l[k].weight);
}

/* Draws every layer bottom to top onto the canvas. Returns 0, or -1 when
 * out of memory. */
static int draw_layers(const synth_scene_params *p, scene_canvas *c, layer_stack *s)
{
    size_t n = (size_t)c->width * c->height;
    float *w;
    scene_backdrop(p, c);
    if (p->shadow.strength > 0) {
        if (!(w = push(s, n, SYNTH_PART_CAST_SHADOW, p->shadow.side, 0)))
            return -1;
        scene_cast_shadow(p, c, w);
    }
    if (p->stand.kind != SYNTH_STAND_NONE && (!(w = push(s, n, SYNTH_PART_STAND, 0, 1)) || scene_stand(p, c, w)))
        return -1;
    if (p->contact_shadow > 0) {
        if (!(w = push(s, n, SYNTH_PART_CONTACT_SHADOW, 0, 0)))
            return -1;
        scene_contact_shadow(p, c, w);
    }
    if (p->vessel_count == 2 && (!(w = push(s, n, SYNTH_PART_SECOND_VESSEL, 0, 1)) || scene_vessel(p, 1, c, w)))
        return -1;
    static const synth_part_kind attach_part[] = {SYNTH_PART_KIND_COUNT, SYNTH_PART_HANDLE, SYNTH_PART_LUG,
                                                  SYNTH_PART_SPOUT};
    for (int k = 0; k < SYNTH_SCENE_MAX_ATTACHMENTS; k++) {
        const synth_attachment *a = &p->attachments[k];
        if (a->kind == SYNTH_ATTACH_NONE)
            continue;
        if (!(w = push(s, n, attach_part[a->kind], a->side, 1)) || scene_attachment(p, k, c, w))
            return -1;
    }
    if (p->vessel_count >= 1 && (!(w = push(s, n, SYNTH_PART_KIND_COUNT, 0, 1)) || scene_vessel(p, 0, c, w)))
        return -1;
    struct {
        int on;
        synth_part_kind kind;
        void (*draw)(const synth_scene_params *, scene_canvas *, float *);
    } overlays[] = {{p->caption, SYNTH_PART_CAPTION, scene_caption},
                    {p->scale_bar, SYNTH_PART_SCALE_BAR, scene_scale_bar},
                    {p->backdrop.frame, SYNTH_PART_FRAME, scene_frame}};
    for (size_t k = 0; k < sizeof overlays / sizeof overlays[0]; k++) {
        if (!overlays[k].on)
            continue;
        if (!(w = push(s, n, overlays[k].kind, 0, 1)))
            return -1;
        overlays[k].draw(p, c, w);
    }
    return 0;
}

/* Turns each layer's weight into its visible weight: times what the opaque
 * layers above it leave showing (top to bottom, one transmittance buffer). */
static int visible_weights(layer_stack *s, size_t n)
{
    float *through = malloc(n * sizeof *through);
    if (!through)
        return -1;
    for (size_t k = 0; k < n; k++)
        through[k] = 1;
    for (int i = s->count - 1; i >= 0; i--) {
        float *w = s->l[i].weight;
        for (size_t k = 0; k < n; k++) {
            float cover = w[k];
            w[k] *= through[k];
            if (s->l[i].occludes)
                through[k] *= 1 - cover;
        }
    }
    free(through);
    return 0;
}

/* The camera: Rec.601 luma when grayscale, sensor noise, JPEG quantisation. */
static void develop(const synth_scene_params *p, const scene_canvas *c, image_t *img)
{
    int C = img->channels;
    for (size_t k = 0; k < (size_t)c->width * c->height; k++) {
        const float *rgb = c->rgb + 3 * k;
        float luma = 0.299f * rgb[0] + 0.587f * rgb[1] + 0.114f * rgb[2];
        for (int q = 0; q < C; q++) {
            double v = C == 1 ? luma : rgb[q];
            if (p->noise > 0)
                v += p->noise * synth_noise_gauss(p->seed, (int)(k % c->width), (int)(k / c->width), q);
            img->data[k * C + q] = (float)fmin(1, fmax(0, v));
        }
    }
    if (p->jpeg_quality > 0)
        synth_jpeg_quantise(img, p->jpeg_quality);
}

/* ------------------------------------------------------------------ truth */

static void part_extent(const layer *l, int width, int height, double axis_x, synth_part_truth *t)
{
    const float threshold = 0.02f;
    t->kind = l->kind;
    t->row0 = t->row1 = t->col0 = t->col1 = -1;
    for (int j = 0; j < height; j++)
        for (int i = 0; i < width; i++)
            if (l->weight[(size_t)j * width + i] >= threshold) {
                if (t->row0 < 0 || j < t->row0)
                    t->row0 = j;
                if (t->col0 < 0 || i < t->col0)
                    t->col0 = i;
                t->row1 = j > t->row1 ? j : t->row1;
                t->col1 = i > t->col1 ? i : t->col1;
            }
    t->side = l->side;
    if (t->side == 0 && t->row0 >= 0)
        t->side = t->col1 + 1 <= axis_x ? -1 : t->col0 >= axis_x ? 1 : 0;
}

static void fill_truth(const synth_scene_params *p, const layer_stack *s, int width, int height, synth_scene_truth *t)
{
    memset(t, 0, sizeof *t);
    t->vessel_count = p->vessel_count;
    t->foot_y = NAN;
    double axis_x = 0.5 * width;
    if (p->vessel_count >= 1) {
        const synth_body *b = &p->vessels[0].body;
        double se = sin(b->elevation_deg * M_PI / 180), y_bottom;
        t->body = *b;
        t->axis_origin = t->base_center = b->base_center;
        t->axis_direction = synth_body_axis(b);
        t->rim_center = synth_body_rim_center(b);
        t->base_half_height = synth_body_radius(b, 0) * se;
        t->rim_half_height = synth_body_radius(b, b->height_px) * se;
        synth_body_corners(b, t->corners);
        synth_body_y_extent(b, &t->outline_top_y, &y_bottom);
        if (b->tilt_deg != 0)
            t->outline_top_y = fmin(t->corners[CORNER_RIM_LEFT].y, t->corners[CORNER_RIM_RIGHT].y);
        t->outline_bottom_y = scene_foot_y(p);
        if (p->stand.kind != SYNTH_STAND_NONE || p->shadow.strength > 0 || p->contact_shadow > 0)
            t->foot_y = t->outline_bottom_y;
        axis_x = b->base_center.x;
    }
    for (int i = 0; i < s->count; i++) {
        const layer *l = &s->l[i];
        if (l->kind == SYNTH_PART_KIND_COUNT) {
            for (int j = 0; j < height; j++)
                for (int k = 0; k < width; k++)
                    if ((j == 0 || j == height - 1 || k == 0 || k == width - 1) && l->weight[(size_t)j * width + k] > 0)
                        t->touches_border = 1;
            continue;
        }
        part_extent(l, width, height, axis_x, &t->parts[t->part_count++]);
    }
}

int synth_scene_draw(const synth_scene_params *p, image_t *img, image_t *body_mask, synth_scene_truth *truth)
{
    memset(img, 0, sizeof *img);
    if (body_mask)
        memset(body_mask, 0, sizeof *body_mask);
    if (!params_valid(p))
        return -1;
    int W = p->width, H = p->height;
    size_t n = (size_t)W * H;
    scene_canvas canvas = {W, H, malloc(3 * n * sizeof(float))};
    layer_stack stack = {0};
    *img = image_alloc(W, H, p->grayscale ? 1 : 3);
    if (body_mask)
        *body_mask = image_alloc(W, H, 1);
    int rc = -1;
    if (canvas.rgb && img->data && (!body_mask || body_mask->data) && draw_layers(p, &canvas, &stack) == 0 &&
        visible_weights(&stack, n) == 0) {
        develop(p, &canvas, img);
        for (int i = 0; i < stack.count; i++)
            if (body_mask && stack.l[i].kind == SYNTH_PART_KIND_COUNT)
                memcpy(body_mask->data, stack.l[i].weight, n * sizeof(float));
        if (truth)
            fill_truth(p, &stack, W, H, truth);
        rc = 0;
    }
    free(canvas.rgb);
    free_layers(&stack);
    if (rc) {
        image_free(img);
        if (body_mask)
            image_free(body_mask);
    }
    return rc;
}

double synth_scene_radius(const synth_scene_truth *t, double h) { return synth_body_radius(&t->body, h); }

int synth_scene_outline_x(const synth_scene_truth *t, double y, double *x_left, double *x_right)
{
    return t->vessel_count >= 1 && synth_body_outline_x(&t->body, y, x_left, x_right);
}

const char *synth_part_name(synth_part_kind kind)
{
    static const char *const names[SYNTH_PART_KIND_COUNT] = {
        "handle", "lug", "spout", "stand", "cast_shadow", "contact_shadow", "second_vessel", "caption", "scale_bar",
        "frame"};
    return (unsigned)kind < SYNTH_PART_KIND_COUNT ? names[kind] : NULL;
}

/* ------------------------------------------------------------------ the named cases */

/* A case: where the subject stands, relative to the image, and the rest of
 * the scene. synth_scene_case fills in the vessels' height_px and
 * base_center. Lengths inside `scene` are already relative (fractions of H). */
typedef struct {
    const char *name, *what;
    double height;        /* the subject's H over the image height ... */
    double fit;           /* ... shrunk so its widest point takes at most this share of the image width */
    double base_y;        /* the base centre's y over the image height (> 1: below the bottom border) */
    double center_x;      /* the axis's x over the image width */
    double second_x;      /* the second vessel's axis x over the image width */
    double second_height; /* the second vessel's H over the subject's */
    synth_scene_params scene;
} scene_case;

/* Colours (encoded values). */
#define CELADON {0.50f, 0.62f, 0.53f}
#define INLAY_WHITE {0.90f, 0.89f, 0.82f}
#define TENMOKU {0.13f, 0.09f, 0.07f}
#define RUST {0.55f, 0.30f, 0.13f}
#define PORCELAIN {0.90f, 0.90f, 0.87f}
#define COBALT {0.16f, 0.22f, 0.52f}
#define BLACK_GLAZE {0.10f, 0.09f, 0.08f}
#define TERRACOTTA {0.74f, 0.52f, 0.36f}
#define STAND_WHITE {0.93f, 0.93f, 0.92f}

/* Backdrops. The museum's sweeps brighten from a mid-grey wall at the top
 * (~0.35 encoded) to a light floor at the bottom (~0.88) over most of the
 * image height, fastest a little under the vessels' feet. */
#define SWEEP(top, bottom, mid, width, vign, ...)                                                                     \
    {.kind = SYNTH_BACKDROP_SWEEP, .wall = {top, top, top + 0.01f}, .floor = {bottom, bottom, bottom - 0.01f},        \
     .horizon = (mid), .softness = (width), .vignette = (vign), __VA_ARGS__}
#define SWEEP_GREY SWEEP(0.33f, 0.95f, 0.68, 0.17, 0.15, .frame = 0)
#define SWEEP_LIGHT SWEEP(0.62f, 0.97f, 0.70, 0.20, 0.10, .frame = 0)
#define FLAT_LIGHT {.kind = SYNTH_BACKDROP_FLAT, .wall = {0.93f, 0.93f, 0.92f}}
#define FLAT_BW {.kind = SYNTH_BACKDROP_FLAT, .wall = {0.80f, 0.80f, 0.80f}, .vignette = 0.12}
#define BLACK_CLOTH {.kind = SYNTH_BACKDROP_FLAT, .wall = {0.03f, 0.03f, 0.03f}}
#define PAPER                                                                                                          \
    {.kind = SYNTH_BACKDROP_FLAT, .wall = {0.90f, 0.87f, 0.80f}, .vignette = 0.3, .grain = 0.05, .grain_px = 48,       \
     .frame = 1}

/* A vessel in one flat colour (for exact outline tests), and a lit one with
 * a highlight stripe of some strength at an azimuth; sizes are filled in by
 * synth_scene_case. */
#define FLAT(prof, elev, ...)                                                                                         \
    .body = {.profile = (prof), .radius_scale = 1, .elevation_deg = (elev)}, .glaze = __VA_ARGS__
#define LIT(prof, elev, colour, stripe, stripe_deg)                                                                   \
    FLAT(prof, elev, colour), .lit = 1, .highlight = (stripe), .highlight_deg = (stripe_deg), .highlight_width_deg = 8
#define DECOR(kind, colour) .decor = SYNTH_DECOR_##kind, .decor_colour = colour

/* Attachments: side, the two heights, reach and thickness (fractions of H). */
#define HANDLE(side, h0, h1, reach, thick) {SYNTH_ATTACH_HANDLE, side, h0, h1, reach, thick}
#define SPOUT(side, h0, h1, reach, thick) {SYNTH_ATTACH_SPOUT, side, h0, h1, reach, thick}
#define LUG(side, h, reach, thick) {SYNTH_ATTACH_LUG, side, h, h, reach, thick}

/* A museum's JPEG: a little sensor noise, quality 90. */
#define MUSEUM_JPEG .noise = 0.005, .jpeg_quality = 90

#define SHADOW_RIGHT {.strength = 0.45, .side = 1, .length = 0.85, .breadth = 0.10, .rise_deg = 10, .softness = 0.06}
#define SHADOW_LEFT {.strength = 0.40, .side = -1, .length = 0.70, .breadth = 0.09, .rise_deg = 14, .softness = 0.07}

/* Each row: name, what makes it hard; height, fit, base_y, center_x,
 * second_x, second_height (see scene_case); the scene. */
static const scene_case CASES[] = {
    {"maebyeong_flat", "maebyeong in one flat colour on a flat backdrop, level camera: the exact-outline reference",
     0.80, 0.8, 0.90, 0.5, 0, 0,
     {.backdrop = FLAT_LIGHT, .vessel_count = 1, .vessels = {{FLAT(SYNTH_PROFILE_MAEBYEONG, 0, CELADON)}}}},
    {"maebyeong_studio", "celadon maebyeong on a grey sweep: inlaid roundels, a highlight stripe on the right outline",
     0.72, 0.8, 0.86, 0.5, 0, 0,
     {.backdrop = SWEEP_GREY, .vessel_count = 1,
      .vessels = {{LIT(SYNTH_PROFILE_MAEBYEONG, 0, CELADON, 0.45, 80), DECOR(MEDALLIONS, INLAY_WHITE)}},
      .contact_shadow = 0.5, MUSEUM_JPEG}},
    {"maebyeong_shadow", "the studio maebyeong with a soft floor shadow on the right running up the sweep",
     0.72, 0.8, 0.86, 0.5, 0, 0,
     {.backdrop = SWEEP_GREY, .vessel_count = 1,
      .vessels = {{LIT(SYNTH_PROFILE_MAEBYEONG, 0, CELADON, 0.45, 80), DECOR(MEDALLIONS, INLAY_WHITE)}},
      .shadow = SHADOW_RIGHT, .contact_shadow = 0.5, MUSEUM_JPEG}},
    {"maebyeong_high", "maebyeong seen 12 deg from above: base and rim are ellipse arcs, the mouth shows; shadow left",
     0.72, 0.8, 0.86, 0.5, 0, 0,
     {.backdrop = SWEEP_GREY, .vessel_count = 1,
      .vessels = {{LIT(SYNTH_PROFILE_MAEBYEONG, 12, CELADON, 0.45, 0), .open_mouth = 1}},
      .shadow = SHADOW_LEFT, .contact_shadow = 0.5, MUSEUM_JPEG}},
    {"ewer_neck", "pear-shaped tenmoku bottle, narrow neck under a rounded shoulder, glossy stripe on the left outline",
     0.76, 0.8, 0.88, 0.5, 0, 0,
     {.backdrop = SWEEP_LIGHT, .vessel_count = 1,
      .vessels = {{LIT(SYNTH_PROFILE_EWER, 0, TENMOKU, 0.6, -82), DECOR(BANDS, RUST)}},
      .contact_shadow = 0.6, MUSEUM_JPEG}},
    {"ewer_handle_spout", "celadon ewer with a loop handle on the right and a spout on the left",
     0.70, 0.6, 0.86, 0.5, 0, 0,
     {.backdrop = SWEEP_GREY, .vessel_count = 1, .vessels = {{LIT(SYNTH_PROFILE_EWER, 0, CELADON, 0.45, 30)}},
      .attachments = {HANDLE(1, 0.32, 0.80, 0.12, 0.045), SPOUT(-1, 0.36, 0.58, 0.10, 0.10)},
      .contact_shadow = 0.5, MUSEUM_JPEG}},
    {"lidded_jar", "blue-and-white lidded jar, level camera: domed lid and knob are part of the profile; shadow left",
     0.76, 0.8, 0.87, 0.5, 0, 0,
     {.backdrop = SWEEP_GREY, .vessel_count = 1,
      .vessels = {{LIT(SYNTH_PROFILE_LIDDED_JAR, 0, PORCELAIN, 0.45, 40), DECOR(BANDS, COBALT)}},
      .shadow = SHADOW_LEFT, .contact_shadow = 0.5, MUSEUM_JPEG}},
    {"lidded_jar_flat_high", "flat-colour lidded jar seen 10 deg from above on a flat backdrop: exact elliptic caps",
     0.78, 0.8, 0.86, 0.5, 0, 0,
     {.backdrop = FLAT_LIGHT, .vessel_count = 1, .vessels = {{FLAT(SYNTH_PROFILE_LIDDED_JAR, 10, COBALT)}}}},
    {"lidded_jar_high", "lidded jar 8 deg from above under studio light, with a floor shadow to the right",
     0.74, 0.8, 0.86, 0.5, 0, 0,
     {.backdrop = SWEEP_GREY, .vessel_count = 1,
      .vessels = {{LIT(SYNTH_PROFILE_LIDDED_JAR, 8, PORCELAIN, 0.45, -30), DECOR(BANDS, COBALT)}},
      .shadow = SHADOW_RIGHT, .contact_shadow = 0.5, MUSEUM_JPEG}},
    {"amphora_handles", "black-glazed amphora with two loop handles from shoulder to neck and painted bands",
     0.74, 0.6, 0.86, 0.5, 0, 0,
     {.backdrop = SWEEP_GREY, .vessel_count = 1,
      .vessels = {{LIT(SYNTH_PROFILE_VASE, 0, BLACK_GLAZE, 0.45, 70), DECOR(BANDS, TERRACOTTA)}},
      .attachments = {HANDLE(-1, 0.45, 0.86, 0.09, 0.03), HANDLE(1, 0.45, 0.86, 0.09, 0.03)},
      .contact_shadow = 0.5, MUSEUM_JPEG}},
    {"jar_lugs_high", "terracotta jar seen 15 deg from above with two solid lugs, a frame line, a shadow to the right",
     0.62, 0.7, 0.84, 0.5, 0, 0,
     {.backdrop = SWEEP(0.36f, 0.95f, 0.66, 0.16, 0.2, .frame = 1), .vessel_count = 1,
      .vessels = {{LIT(SYNTH_PROFILE_JAR, 15, TERRACOTTA, 0.45, 0), .open_mouth = 1, DECOR(MEDALLIONS, RUST)}},
      .attachments = {LUG(-1, 0.84, 0.07, 0.13), LUG(1, 0.84, 0.07, 0.13)},
      .shadow = SHADOW_RIGHT, .contact_shadow = 0.5, MUSEUM_JPEG}},
    {"bottle_stand", "dark glossy bottle on a white cylinder stand a little wider than its foot, off the bottom border",
     0.56, 0.8, 0.78, 0.5, 0, 0,
     {.backdrop = SWEEP_LIGHT, .vessel_count = 1, .vessels = {{LIT(SYNTH_PROFILE_BOTTLE, 0, BLACK_GLAZE, 0.45, 60)}},
      .stand = {SYNTH_STAND_CYLINDER, 1.15, 1.2, 0, STAND_WHITE}, .contact_shadow = 0.35, MUSEUM_JPEG}},
    {"footed_bowl_stand", "terracotta footed bowl on a narrower white stand (a waist at the foot), near-white backdrop",
     0.36, 0.85, 0.55, 0.5, 0, 0,
     {.backdrop = FLAT_LIGHT, .vessel_count = 1,
      .vessels = {{LIT(SYNTH_PROFILE_FOOTED_BOWL, 0, TERRACOTTA, 0.45, 50), DECOR(BANDS, BLACK_GLAZE)}},
      .stand = {SYNTH_STAND_CYLINDER, 0.8, 2.0, 0, STAND_WHITE}, MUSEUM_JPEG}},
    {"vase_plinth", "vase on a white box plinth wider than its foot, camera 6 deg above (the plinth's top shows)",
     0.66, 0.8, 0.76, 0.5, 0, 0,
     {.backdrop = SWEEP_GREY, .vessel_count = 1,
      .vessels = {{LIT(SYNTH_PROFILE_VASE, 6, CELADON, 0.45, 20), .open_mouth = 1, DECOR(BANDS, INLAY_WHITE)}},
      .stand = {SYNTH_STAND_BOX, 1.8, 0.16, 0.8, STAND_WHITE}, .shadow = SHADOW_RIGHT, .contact_shadow = 0.4,
      MUSEUM_JPEG}},
    {"two_vessels", "a maebyeong and a smaller jar side by side on one sweep (refuse: two vessels)",
     0.66, 0.45, 0.86, 0.34, 0.76, 0.62,
     {.backdrop = SWEEP_GREY, .vessel_count = 2,
      .vessels = {{LIT(SYNTH_PROFILE_MAEBYEONG, 0, CELADON, 0.45, 40)},
                  {LIT(SYNTH_PROFILE_JAR, 0, TERRACOTTA, 0.45, 40)}},
      .contact_shadow = 0.5, MUSEUM_JPEG}},
    {"vase_cut_bottom", "vase cut by the image's bottom border (refuse: border contact)",
     0.92, 0.8, 1.10, 0.5, 0, 0,
     {.backdrop = SWEEP_GREY, .vessel_count = 1, .vessels = {{LIT(SYNTH_PROFILE_VASE, 0, CELADON, 0.45, 40)}},
      MUSEUM_JPEG}},
    {"beaker_caption_bw", "black-and-white photo of a near-cylindrical jar on plain grey, a caption and a scale bar",
     0.74, 0.8, 0.84, 0.5, 0, 0,
     {.backdrop = FLAT_BW, .vessel_count = 1, .vessels = {{LIT(SYNTH_PROFILE_JAR, 0, PORCELAIN, 0.3, 60)}},
      .caption = 1, .scale_bar = 1, .grayscale = 1, .noise = 0.01}},
    {"jar_handles_bw", "black-and-white two-handled jar, dark on light, with JPEG artefacts",
     0.70, 0.55, 0.86, 0.5, 0, 0,
     {.backdrop = FLAT_BW, .vessel_count = 1,
      .vessels = {{LIT(SYNTH_PROFILE_JAR, 0, TERRACOTTA, 0.45, 40), DECOR(MEDALLIONS, BLACK_GLAZE)}},
      .attachments = {HANDLE(-1, 0.40, 0.88, 0.12, 0.04), HANDLE(1, 0.40, 0.88, 0.12, 0.04)},
      .contact_shadow = 0.4, .grayscale = 1, .jpeg_quality = 70}},
    {"vase_black", "white porcelain vase lit on a black backdrop",
     0.76, 0.8, 0.88, 0.5, 0, 0,
     {.backdrop = BLACK_CLOTH, .vessel_count = 1, .vessels = {{LIT(SYNTH_PROFILE_VASE, 0, PORCELAIN, 0.45, 40)}},
      .noise = 0.01}},
    {"bowl_paper", "footed bowl on textured paper with vignetting and a thin dark frame line",
     0.40, 0.8, 0.72, 0.5, 0, 0,
     {.backdrop = PAPER, .vessel_count = 1,
      .vessels = {{LIT(SYNTH_PROFILE_FOOTED_BOWL, 0, TERRACOTTA, 0.45, 30), DECOR(BANDS, BLACK_GLAZE)}},
      .contact_shadow = 0.5, .jpeg_quality = 85}},
    {"white_on_grey", "white-glazed jar on a light grey sweep (low contrast), highlight on the right outline, JPEG 60",
     0.74, 0.8, 0.86, 0.5, 0, 0,
     {.backdrop = SWEEP(0.80f, 0.90f, 0.82, 0.06, 0.1, .frame = 0), .vessel_count = 1,
      .vessels = {{LIT(SYNTH_PROFILE_JAR, 0, PORCELAIN, 0.6, 82)}}, .contact_shadow = 0.3, .jpeg_quality = 60}},
    {"backdrop_only", "the grey sweep with vignetting, paper grain and sensor noise, and no vessel",
     0.7, 0.8, 0.86, 0.5, 0, 0,
     {.backdrop = SWEEP(0.33f, 0.95f, 0.68, 0.17, 0.15, .grain = 0.02, .grain_px = 64), .noise = 0.01}},
    {"bottle_tilted", "bottle leaning 3 deg in the image plane (level camera), a shadow on the right",
     0.74, 0.8, 0.88, 0.5, 0, 0,
     {.backdrop = SWEEP_GREY, .vessel_count = 1,
      .vessels = {{LIT(SYNTH_PROFILE_BOTTLE, 0, CELADON, 0.45, 40), .body.tilt_deg = 3}},
      .shadow = SHADOW_RIGHT, .contact_shadow = 0.5, MUSEUM_JPEG}},
};

enum { CASE_COUNT = sizeof CASES / sizeof CASES[0] };

int synth_scene_case_count(void) { return CASE_COUNT; }

const char *synth_scene_case_name(int i) { return i >= 0 && i < CASE_COUNT ? CASES[i].name : NULL; }

const char *synth_scene_case_description(int i) { return i >= 0 && i < CASE_COUNT ? CASES[i].what : NULL; }

/* Sets a body's height so it fits `height` of the image height and `fit` of
 * the image width, standing on (x, base_y). */
static void place(synth_body *b, double height, double fit, double x, double base_y, int width)
{
    double widest = 2 * b->radius_scale * synth_profile_max_radius(b->profile);
    b->height_px = fmin(height, fit * width / widest);
    b->base_center = v2(x, base_y);
}

int synth_scene_case(const char *name, int width, int height, synth_scene_params *p)
{
    for (int i = 0; i < CASE_COUNT; i++) {
        const scene_case *c = &CASES[i];
        if (strcmp(c->name, name) != 0)
            continue;
        *p = c->scene;
        p->width = width;
        p->height = height;
        p->seed = 0x5eed0000u + (uint32_t)i;
        if (p->vessel_count >= 1)
            place(&p->vessels[0].body, c->height * height, c->fit, c->center_x * width, c->base_y * height, width);
        if (p->vessel_count == 2)
            place(&p->vessels[1].body, c->second_height * p->vessels[0].body.height_px, c->fit,
                  c->second_x * width, c->base_y * height, width);
        return 0;
    }
    return -1;
}
