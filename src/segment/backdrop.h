/* The backdrop of a catalogue photograph as a smooth colour field: a sweep,
 * a vignetted wall, a lit floor. A tensor-product cubic B-spline surface per
 * channel, fitted robustly to the pixels known to be backdrop and bent as
 * little as possible where none are (behind the object). */
#ifndef CELADON_SEGMENT_BACKDROP_H
#define CELADON_SEGMENT_BACKDROP_H

#include <stdint.h>

enum { RECON_BACKDROP_MAX_GRID = 16 };

typedef struct {
    int grid;            /* control points per side (4..RECON_BACKDROP_MAX_GRID) */
    int width, height;   /* the image it models */
    double coef[RECON_BACKDROP_MAX_GRID * RECON_BACKDROP_MAX_GRID][4]; /* colour, 0 (a vector's padding) */
    double cov[9];       /* covariance of the residuals of the backdrop pixels (noise, texture, misfit) */
} recon_backdrop;

/* Fits the surface to the pixels of rgb (w*h*3) where use[p] is set, taking
 * every step-th pixel in x and y; Tukey-weighted least squares repeated
 * `rounds` times, so objects that slipped into `use` (a stand at the border,
 * a frame line) weigh nothing. The smoothness penalty on second differences
 * of the control points decides where there is no data. Returns 0, or -1
 * when fewer than grid^2 pixels are usable or out of memory. */
int recon_backdrop_fit(recon_backdrop *b, const float *rgb, int w, int h, const uint8_t *use, int step, int grid,
                       int rounds);

/* The modelled backdrop colour at the continuous position (x, y). */
void recon_backdrop_at(const recon_backdrop *b, double x, double y, double out[3]);

/* The same from the basis of x and of y (the first control point and the four
 * weights along each), for callers that evaluate many points on a grid. */
typedef struct {
    int first;
    double wt[4];
} recon_backdrop_basis;
void recon_backdrop_basis_x(const recon_backdrop *b, double x, recon_backdrop_basis *out);
void recon_backdrop_basis_y(const recon_backdrop *b, double y, recon_backdrop_basis *out);
void recon_backdrop_at_basis(const recon_backdrop *b, const recon_backdrop_basis *bx, const recon_backdrop_basis *by,
                             double out[3]);

/* The surface along one row collapsed by the row's basis by: one colour per
 * control column (col[0..grid)); a point of that row is then
 * recon_backdrop_at_collapsed, 12 products instead of 48. */
void recon_backdrop_collapse_row(const recon_backdrop *b, const recon_backdrop_basis *by,
                                 double col[RECON_BACKDROP_MAX_GRID][3]);
void recon_backdrop_at_collapsed(const double col[RECON_BACKDROP_MAX_GRID][3], const recon_backdrop_basis *bx,
                                 float out[3]);

/* The modelled backdrop colour of every pixel of row y (out: w*3). */
void recon_backdrop_row(const recon_backdrop *b, int y, float *out);

#endif
