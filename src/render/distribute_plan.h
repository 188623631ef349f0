/* How a distributed render cuts its samples into units, and how a process
 * tells that mpirun or srun started it. Private to src/render/ (the MPI and
 * the serial distribute_*.c share it). */
#ifndef CELADON_DISTRIBUTE_PLAN_H
#define CELADON_DISTRIBUTE_PLAN_H

#include <stdint.h>

/* The units of a render of samples [s0, s1) of a width x height film, in
 * the order they are handed out: unit u is pass u / bands (samples
 * [s0 + pass * pass_spp, ...) of every pixel) over band u % bands of rows
 * (rows [band * band_rows, ...)). Passes come first, so an interrupted
 * render has every pixel sampled about evenly. */
typedef struct {
    int s0, s1, width, height;
    int pass_spp, passes;
    int band_rows, bands;
    int units;
} distribute_plan;

/* Units smaller than this many camera samples (about 30 ms of one core at
 * the showcase's 1.8 us per sample) are not made: the hand-out of a unit
 * costs a message to rank 0 and back. */
enum { DISTRIBUTE_MIN_UNIT = 1 << 14 };
/* Units per rank aimed at: the last unit to finish leaves the others idle
 * for about 1/DISTRIBUTE_UNITS_PER_RANK of a rank's share. */
enum { DISTRIBUTE_UNITS_PER_RANK = 32 };
/* Nor are units larger than this (about 7 s of one core at 1.8 us per
 * sample) made: a stop and the progress bar wait for units in flight. */
enum { DISTRIBUTE_MAX_UNIT = 1 << 22 };

distribute_plan distribute_plan_make(int s0, int s1, int width, int height, int ranks);

/* The samples and rows of unit u. */
void distribute_plan_unit(const distribute_plan *p, int u, int *s0, int *s1, int *y0, int *y1);

#endif
