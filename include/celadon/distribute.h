/* A render shared among the processes of an MPI job (docs/distributed.md):
 * `mpirun -np R celadon render ...` (or `srun`) starts R ranks; every rank
 * builds the scene, the samples are cut into units (a range of samples of
 * every pixel of a band of rows, render_loop.h) that rank 0 hands out one at
 * a time to whichever rank asks (so a slow or busy rank takes fewer), each
 * rank adds its units into a film of its own, and the films are summed on
 * rank 0 (MPI_Reduce), which writes the image. The image is the one-process
 * image of the same seed up to the order of the float additions.
 *
 * MPI is optional at build time: without it (distribute_serial.c) a process
 * is always a job of one rank, and one that mpirun or srun started as one of
 * several ranks is refused by distribute_begin (it would render the whole
 * image again).
 *
 * Threads: every call below is made by the thread that called
 * distribute_begin. */
#ifndef CELADON_DISTRIBUTE_H
#define CELADON_DISTRIBUTE_H

#include <stddef.h>

#include "celadon/render.h"

typedef struct {
    int rank, size; /* this process's rank and the job's size (0 and 1 outside MPI) */
} distribute_job;

/* The number of processes the launcher (mpirun, srun, mpiexec) says the job
 * has: 0 when no launcher started this process, -1 when one did without
 * saying how many. */
int distribute_launched_size(void);
/* This process's rank as the launcher says it (0 when none does), known
 * before distribute_begin. */
int distribute_launched_rank(void);

/* Under Open MPI with every rank on this node (OMPI_COMM_WORLD_LOCAL_SIZE
 * is OMPI_COMM_WORLD_SIZE) and no transport chosen (none of OMPI_MCA_pml,
 * _btl, _mtl set, as mpirun --mca does): chooses shared memory, pml ob1 and
 * btl self,vader (what Open MPI ends up with on a machine without a fabric),
 * so that MPI_Init does not first open and probe the fabrics' components
 * (Debian's psm, psm2, tcp: 0.2 s of every rank's wall time,
 * docs/distributed.md). Returns whether it did; distribute_begin calls it. */
int distribute_prefer_shared_memory(void);

/* Joins the MPI job when mpirun or srun started this process (MPI's
 * environment variables say so); otherwise *job is {0, 1} and MPI is not
 * touched. Returns 0, or -1 with one line in err (empty on the ranks other
 * than 0 when they all fail alike). */
int distribute_begin(distribute_job *job, char *err, size_t errlen);

/* Leaves the MPI job (MPI_Finalize); nothing outside one. */
void distribute_end(void);

/* Collective: every rank passes whether its step (say, building the scene)
 * succeeded. Returns -1 when all did, else the lowest rank that failed, so
 * that only that rank prints its reason. */
int distribute_first_failure(int ok);

/* Collective: render_scene shared among the job's ranks. On rank 0 film
 * receives the sum of every rank's samples and stats counts them all; on
 * the other ranks film is freed before returning and stats is this rank's.
 * A stop request on any rank (SIGINT or SIGTERM: mpirun turns Ctrl-C into
 * SIGTERM to every rank) stops every rank after the samples in flight, and
 * rank 0 still receives what all of them finished. Rank 0 draws the
 * progress of the whole job when opt->progress. In a job of one rank this
 * is render_scene. Returns 0, or -1 with a reason in err on the ranks that
 * failed (err is empty on the others, which only stop). */
int distribute_render(const scene_t *s, const render_options *opt, film_t *film, render_stats *stats, char *err,
                      size_t errlen);

#endif
