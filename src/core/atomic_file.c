#include "core/atomic_file.h"

#include "core/temp_files.h"

#include <stdatomic.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

static atomic_uint temp_counter;

void atomic_temp_name(const char *final_path, char *tmp, size_t tmplen)
{
    const char *slash = strrchr(final_path, '/');
    const char *base = slash ? slash + 1 : final_path;
    const char *dot = strrchr(base, '.');
    int dirlen = (int)(base - final_path);
    int stemlen = dot ? (int)(dot - base) : (int)strlen(base);
    snprintf(tmp, tmplen, "%.*s.%.*s.tmp-%ld-%u%s", dirlen, final_path, stemlen, base,
             (long)getpid(), atomic_fetch_add(&temp_counter, 1u), dot ? dot : "");
    temp_files_hold();
    temp_files_track(tmp);
}

void atomic_temp_done(const char *tmp)
{
    temp_files_forget(tmp);
    temp_files_release();
}

int atomic_file_open(atomic_file *af, const char *final_path)
{
    snprintf(af->final_path, sizeof af->final_path, "%s", final_path);
    atomic_temp_name(final_path, af->temp_path, sizeof af->temp_path);
    af->fp = fopen(af->temp_path, "wb");
    return af->fp ? 0 : -1;
}

int atomic_file_commit(atomic_file *af)
{
    int bad = ferror(af->fp) != 0;
    bad |= fclose(af->fp) != 0;
    af->fp = NULL;
    if (!bad && rename(af->temp_path, af->final_path) == 0) {
        atomic_temp_done(af->temp_path);
        return 0;
    }
    remove(af->temp_path);
    atomic_temp_done(af->temp_path);
    return -1;
}

void atomic_file_abort(atomic_file *af)
{
    if (af->fp)
        fclose(af->fp);
    af->fp = NULL;
    remove(af->temp_path);
    atomic_temp_done(af->temp_path);
}
