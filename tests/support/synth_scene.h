/* Synthetic museum photographs with exact ground truth: a compositor that
 * draws a catalogue-like photo as layers, for the reconstruction's hard-case
 * tests (issue 9: shadows, stands, handles, lids, elevated cameras, two
 * vessels, border contact, captions, black-and-white).
 *
 * Layers, bottom to top, each anti-aliased (exact coverage for the vessels
 * and rectangles, 8x8 or finer supersampling for curved parts):
 *   backdrop (flat or a wall-to-floor sweep; vignetting; paper grain)
 *   cast shadow (multiplicative, on one side of the foot only)
 *   stand or plinth under the foot (a cylinder or a box)
 *   contact shadow (multiplicative, just under the foot)
 *   second vessel, then the subject's handles, lugs and spout, then the
 *   subject's body (a solid of revolution: synth_body.h)
 *   caption and scale bar at the bottom border, frame line
 *   then sensor noise, grayscale, JPEG-like 8x8 quantisation.
 * Colours are encoded values in [0, 1]. Everything random comes from `seed`
 * (synth_noise.h): the same parameters always draw the same image.
 *
 * The named cases (synth_scene_case) live in one table in synth_scene.c;
 * `make hard-cases` draws them all into out/hard-cases/ with a contact sheet.
 *
 *     synth_scene_params p;
 *     synth_scene_case("maebyeong_shadow", 600, 800, &p);
 *     image_t img;  synth_scene_truth t;
 *     synth_scene_draw(&p, &img, NULL, &t);
 *     synth_scene_outline_x(&t, y, &xl, &xr);   // exact body outline on line y
 *     synth_scene_radius(&t, h);                // exact r(h), lid and knob included */
#ifndef CELADON_TESTS_SYNTH_SCENE_H
#define CELADON_TESTS_SYNTH_SCENE_H

#include <stdint.h>

#include "celadon/image.h"

#include "synth_body.h"

typedef enum { SYNTH_BACKDROP_FLAT, SYNTH_BACKDROP_SWEEP } synth_backdrop_kind;

typedef struct {
    synth_backdrop_kind kind;
    float wall[3];   /* FLAT: the colour; SWEEP: the top (the wall) */
    float floor[3];  /* SWEEP: the bottom (the floor) */
    double horizon;  /* SWEEP: row of the S-curve's middle, fraction of the image height */
    double softness; /* SWEEP: the S-curve's logistic scale, fraction of the image height */
    double vignette; /* darkening at the image corners (0: none), growing as the squared radius */
    double grain;    /* relative amplitude of a seeded paper texture (0: none; ~0.03 for paper) */
    double grain_px; /* its largest feature size, px */
    int frame;       /* a thin dark frame line around the whole image */
} synth_backdrop;

typedef enum { SYNTH_DECOR_NONE, SYNTH_DECOR_LINES, SYNTH_DECOR_BANDS, SYNTH_DECOR_MEDALLIONS } synth_decor;

/* A vessel's look. With lit = 0 every body pixel is `glaze` (coverage
 * blended with what lies under it): the cases for exact outline tests. */
typedef struct {
    synth_body body;
    float glaze[3];
    float decor_colour[3];
    synth_decor decor;          /* LINES: a thin line under the shoulder; BANDS: it, another over the foot
                                   and a wide band; MEDALLIONS: the two lines and a ring of roundels */
    int lit;                    /* studio lighting: darker toward the silhouette, lit from the upper left */
    double highlight;           /* strength of a vertical highlight stripe (0: none) */
    double highlight_deg;       /* its azimuth: 0 faces the camera; beyond ±75 it touches the outline */
    double highlight_width_deg; /* its half-width */
    int open_mouth;             /* elevated camera: the rim disc shows a dark interior (else a lit lid top) */
} synth_scene_vessel;

typedef enum { SYNTH_ATTACH_NONE, SYNTH_ATTACH_HANDLE, SYNTH_ATTACH_LUG, SYNTH_ATTACH_SPOUT } synth_attach_kind;

/* A part of the subject that is not a surface of revolution, in the plane of
 * its silhouette on one side, drawn behind the body (its ends vanish in it). */
typedef struct {
    synth_attach_kind kind;
    int side;         /* -1 left, +1 right */
    double h0, h1;    /* HANDLE: heights of its two ends; SPOUT: root and tip; LUG: h0 its centre (fractions of H) */
    double reach;     /* how far it stands out of the wider of r(h0), r(h1), fraction of H */
    double thickness; /* fraction of H (SPOUT: at the root, half at the tip; LUG: its height) */
    float colour[3];  /* its own colour; all 0: the subject's glaze */
} synth_attachment;

typedef enum { SYNTH_STAND_NONE, SYNTH_STAND_CYLINDER, SYNTH_STAND_BOX } synth_stand_kind;

/* A separate body under the subject's foot, centred on its axis. */
typedef struct {
    synth_stand_kind kind;
    double width;  /* its width over the foot's diameter: > 1 wider than the foot, < 1 narrower */
    double height; /* fraction of H; it runs off the bottom border when it reaches past it */
    double depth;  /* BOX: front-to-back depth over its width (its top face shows when elevated) */
    float colour[3];
} synth_stand;

/* A soft shadow on the floor beside the foot, on one side only. */
typedef struct {
    double strength; /* darkening at its core: 0 none, ~0.4 a studio shadow */
    int side;        /* -1 falls to the left, +1 to the right */
    double length;   /* from the axis outward, fraction of H */
    double breadth;  /* its thickness, fraction of H */
    double rise_deg; /* angle above the horizontal at which it runs away (onto the sweep) */
    double softness; /* penumbra width, fraction of H */
} synth_cast_shadow;

enum { SYNTH_SCENE_MAX_ATTACHMENTS = 4 };

typedef struct {
    int width, height;
    uint32_t seed;
    synth_backdrop backdrop;
    int vessel_count;                 /* 0 (backdrop only), 1, or 2 (a second vessel beside the subject) */
    synth_scene_vessel vessels[2];    /* [0] is the subject, the one the truth describes */
    synth_attachment attachments[SYNTH_SCENE_MAX_ATTACHMENTS]; /* on the subject; kind NONE is unused */
    synth_stand stand;                /* under the subject (its camera must not be tilted) */
    synth_cast_shadow shadow;         /* beside the subject's foot */
    double contact_shadow;            /* darkening just under the subject's foot (0: none) */
    int caption;                      /* a label of small dark "text" blocks in the bottom right corner */
    int scale_bar;                    /* a black and white scale bar at the bottom left */
    int grayscale;                    /* one channel: Rec.601 luma of the colour drawing */
    double noise;                     /* sensor noise: standard deviation, encoded units (0: none) */
    int jpeg_quality;                 /* 8x8 DCT quantisation as a JPEG of this quality, 1..100 (0: off) */
    int subrows;                      /* vertical samples per pixel row for the vessels (0: 16) */
    int supersample;                  /* n for n x n samples per pixel of curved parts (0: 8; at least 8) */
} synth_scene_params;

typedef enum {
    SYNTH_PART_HANDLE,
    SYNTH_PART_LUG,
    SYNTH_PART_SPOUT,
    SYNTH_PART_STAND,
    SYNTH_PART_CAST_SHADOW,
    SYNTH_PART_CONTACT_SHADOW,
    SYNTH_PART_SECOND_VESSEL,
    SYNTH_PART_CAPTION,
    SYNTH_PART_SCALE_BAR,
    SYNTH_PART_FRAME,
    SYNTH_PART_KIND_COUNT
} synth_part_kind;

/* Where a non-SOR part shows in the image: the pixels whose visible weight
 * (its coverage, or a shadow's darkening, times what the layers above leave
 * visible) is at least 0.02. Rows and columns are inclusive; -1 when the part
 * does not show at all. */
typedef struct {
    synth_part_kind kind;
    int side; /* -1 left of the subject's axis, +1 right, 0 both sides or centred */
    int row0, row1, col0, col1;
} synth_part_truth;

enum { SYNTH_SCENE_MAX_PARTS = SYNTH_SCENE_MAX_ATTACHMENTS + 8 };

/* What the tests assert against. The body is the subject's solid of
 * revolution only: lid and knob are in its profile; handles, lugs, spout,
 * stand and shadows are not (they are parts). */
typedef struct {
    int vessel_count;
    synth_body body;                 /* the subject (read it through synth_scene_radius / _outline_x) */
    vec2 axis_origin;                /* = base_center */
    vec2 axis_direction;             /* unit, base toward rim */
    vec2 base_center, rim_center;    /* image points of the base and rim discs' centres */
    double base_half_height;         /* r(0) sin e: the base ellipse's half-height, px (0 when level) */
    double rim_half_height;          /* r(H) sin e */
    double outline_top_y;            /* the outline's highest and lowest image y (continuous) */
    double outline_bottom_y;
    vec2 corners[CORNER_COUNT];      /* synth_body_corners */
    double foot_y;                   /* where a stand or a shadow begins under the foot (= outline_bottom_y),
                                        NAN when there is neither */
    int touches_border;              /* the body's drawn coverage reaches an image border pixel */
    int part_count;
    synth_part_truth parts[SYNTH_SCENE_MAX_PARTS];
} synth_scene_truth;

/* Draws the scene into a fresh image (3 channels, or 1 with grayscale; bits
 * = 8). When body_mask is not NULL it receives a 1-channel image of the
 * subject body's visible coverage; when truth is not NULL it is filled.
 * Returns 0, or -1 when out of memory or the parameters are invalid (a body
 * synth_body_valid refuses, a tilted camera with a stand, an image under
 * 8x8 or over 1e8 pixels); nothing is allocated then. */
int synth_scene_draw(const synth_scene_params *p, image_t *img, image_t *body_mask, synth_scene_truth *truth);

/* The subject's exact radius at height h (px), and its exact outline on the
 * horizontal line y (as synth_body_outline_x). */
double synth_scene_radius(const synth_scene_truth *t, double h);
int synth_scene_outline_x(const synth_scene_truth *t, double y, double *x_left, double *x_right);

/* The named hard cases: synth_scene_case fills *p with the case laid out on
 * a width x height image (every size and position scales with the image).
 * Returns 0, or -1 for an unknown name. */
int synth_scene_case_count(void);
const char *synth_scene_case_name(int i);        /* NULL out of range */
const char *synth_scene_case_description(int i); /* one line: what makes it hard */
int synth_scene_case(const char *name, int width, int height, synth_scene_params *p);

/* "handle", "cast_shadow", ...; NULL out of range. */
const char *synth_part_name(synth_part_kind kind);

#endif
