/* The units of a distributed render (distribute_plan.h), and the launcher's
 * environment. */
#include "render/distribute_plan.h"

#include "celadon/distribute.h"

#include <stdlib.h>
#include <string.h>

enum { ROW_ALIGN = 16 };       /* the render loop's tile size: bands of whole tiles */
enum { MOST_UNITS = 1 << 24 }; /* so that passes x bands stays an int (at most about twice this) */

static long long ceil_div(long long a, long long b) { return (a + b - 1) / b; }

distribute_plan distribute_plan_make(int s0, int s1, int width, int height, int ranks)
{
    distribute_plan p = {s0, s1, width, height, 1, 0, height, 1, 0};
    long long spp = s1 - s0, pixels = (long long)width * height;
    long long target = (long long)DISTRIBUTE_UNITS_PER_RANK * (ranks > 0 ? ranks : 1);
    if (target < ceil_div(spp * pixels, DISTRIBUTE_MAX_UNIT))
        target = ceil_div(spp * pixels, DISTRIBUTE_MAX_UNIT);
    if (target > MOST_UNITS)
        target = MOST_UNITS;
    /* Whole-image passes first: pass_spp samples of every pixel, at least
     * DISTRIBUTE_MIN_UNIT samples, about `target` of them. */
    long long pass = spp / target;
    long long least = ceil_div(DISTRIBUTE_MIN_UNIT, pixels);
    if (pass < least)
        pass = least;
    if (pass < 1)
        pass = 1;
    if (pass > spp)
        pass = spp;
    p.pass_spp = (int)pass;
    p.passes = (int)ceil_div(spp, pass);
    /* Too few passes (few samples, many ranks): cut each into bands of rows,
     * each still of at least DISTRIBUTE_MIN_UNIT samples. */
    long long bands = ceil_div(target, p.passes);
    long long most = pixels * pass / DISTRIBUTE_MIN_UNIT;
    if (bands > most)
        bands = most;
    if (bands > ceil_div(height, ROW_ALIGN))
        bands = ceil_div(height, ROW_ALIGN);
    if (bands < 1)
        bands = 1;
    p.band_rows = (int)(ceil_div(ceil_div(height, bands), ROW_ALIGN) * ROW_ALIGN);
    if (p.band_rows > height)
        p.band_rows = height;
    p.bands = (int)ceil_div(height, p.band_rows);
    p.units = p.passes * p.bands;
    return p;
}

void distribute_plan_unit(const distribute_plan *p, int u, int *s0, int *s1, int *y0, int *y1)
{
    int pass = u / p->bands, band = u % p->bands;
    *s0 = p->s0 + pass * p->pass_spp;
    *s1 = *s0 + p->pass_spp < p->s1 ? *s0 + p->pass_spp : p->s1;
    *y0 = band * p->band_rows;
    *y1 = *y0 + p->band_rows < p->height ? *y0 + p->band_rows : p->height;
}

int distribute_launched_size(void)
{
    /* Open MPI's mpirun, MPICH's and Slurm's PMI; a PMIx launcher (srun
     * --mpi=pmix) gives the rank only, Slurm the step's task count. */
    static const char *const sizes[] = {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "SLURM_STEP_NUM_TASKS"};
    int launched = getenv("OMPI_COMM_WORLD_SIZE") || getenv("PMI_RANK") || getenv("PMIX_RANK");
    if (!launched)
        return 0;
    for (int i = 0; i < 3; i++) {
        const char *v = getenv(sizes[i]);
        if (v && atoi(v) > 0)
            return atoi(v);
    }
    return -1;
}

int distribute_launched_rank(void)
{
    static const char *const ranks[] = {"OMPI_COMM_WORLD_RANK", "PMI_RANK", "PMIX_RANK", "SLURM_PROCID"};
    for (int i = 0; i < 4; i++) {
        const char *v = getenv(ranks[i]);
        if (v && atoi(v) > 0)
            return atoi(v);
    }
    return 0;
}

int distribute_prefer_shared_memory(void)
{
    const char *size = getenv("OMPI_COMM_WORLD_SIZE"), *local = getenv("OMPI_COMM_WORLD_LOCAL_SIZE");
    if (!size || !local || strcmp(size, local) != 0)
        return 0;
    static const char *const chosen[] = {"OMPI_MCA_pml", "OMPI_MCA_btl", "OMPI_MCA_mtl"};
    for (int i = 0; i < 3; i++)
        if (getenv(chosen[i]))
            return 0;
    setenv("OMPI_MCA_pml", "ob1", 0);
    setenv("OMPI_MCA_btl", "self,vader", 0);
    return 1;
}
