/* distribute.h built without MPI: every job has one rank. A process that a
 * launcher started as one of several ranks is refused, since it would render
 * the whole image again beside the others. */
#include <stdio.h>
#include <unistd.h>

#include "celadon/distribute.h"
#include "render/distribute_plan.h"

int distribute_begin(distribute_job *job, char *err, size_t errlen)
{
    *job = (distribute_job){0, 1};
    int size = distribute_launched_size();
    if (size > 1 || size < 0) {
        /* Rank 0 alone says why; the others wait a moment first, since the
         * launcher ends the job when the first process fails. */
        err[0] = '\0';
        if (distribute_launched_rank() == 0)
            snprintf(err, errlen,
                     "this celadon was built without MPI, so each of the job's processes would render the whole "
                     "image (install Open MPI's libopenmpi-dev, e.g. make deps, and rebuild; docs/distributed.md)");
        else
            sleep(2);
        return -1;
    }
    return 0;
}

void distribute_end(void) {}

int distribute_first_failure(int ok) { return ok ? -1 : 0; }

int distribute_render(const scene_t *s, const render_options *opt, film_t *film, render_stats *stats, char *err,
                      size_t errlen)
{
    return render_scene(s, opt, film, stats, err, errlen);
}
