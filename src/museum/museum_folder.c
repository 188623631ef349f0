/* The museum's output folder. See museum_folder.h. */
#include "core/core.h"
#include "museum/museum_folder.h"

#include <errno.h>
#include <ftw.h>
#include <jansson.h>
#include <stdatomic.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>


static atomic_uint temp_counter;

/* nftw has no user pointer: the walk's state, one walk at a time. */
static _Thread_local struct {
    size_t root_len;
    json_t *files;
    char stray[PATH_MAX];
} walk;

static int listed(const char *rel)
{
    size_t i;
    json_t *v;
    json_array_foreach(walk.files, i, v)
        if (json_is_string(v) && !strcmp(json_string_value(v), rel))
            return 1;
    return 0;
}

static int visit(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
    (void)st;
    if (ftw->level == 0 || flag == FTW_D || flag == FTW_DP)
        return 0;
    const char *rel = path + walk.root_len + 1;
    if (flag != FTW_F || !listed(rel)) {
        snprintf(walk.stray, sizeof walk.stray, "%s", rel);
        return 1;
    }
    return 0;
}

static int is_empty(const char *dir)
{
    walk.files = NULL;
    walk.root_len = strlen(dir);
    return nftw(dir, visit, 16, FTW_PHYS) == 0;
}

int museum_folder_check(const char *dir, char *err, size_t errlen)
{
    struct stat st;
    if (stat(dir, &st) != 0)
        return errno == ENOENT ? 0 : (snprintf(err, errlen, "%s: %s", dir, strerror(errno)), -1);
    if (!S_ISDIR(st.st_mode)) {
        snprintf(err, errlen, "%s: exists and is not a folder", dir);
        return -1;
    }
    char manifest[PATH_MAX + 32];
    snprintf(manifest, sizeof manifest, "%s/%s", dir, MUSEUM_MANIFEST);
    json_t *m = json_load_file(manifest, 0, NULL);
    walk.files = json_object_get(m, "files");
    walk.root_len = strlen(dir);
    walk.stray[0] = 0;
    int ours = json_is_object(json_object_get(m, "celadon_museum")) && json_is_array(walk.files) &&
               nftw(dir, visit, 16, FTW_PHYS) == 0;
    json_decref(m);
    walk.files = NULL;
    if (ours || (!m && is_empty(dir)))
        return 0;
    snprintf(err, errlen, "%s: exists and is not a museum (it holds %s); give a new or empty folder", dir,
             walk.stray[0] ? walk.stray : "files celadon did not write");
    return -1;
}

int museum_folder_begin(const char *dir, char *tmp, size_t len, char *err, size_t errlen)
{
    char parent[PATH_MAX], made[8][PATH_MAX];
    const char *slash = strrchr(dir, '/');
    int n_made = 0;
    snprintf(parent, sizeof parent, "%.*s", slash ? (int)(slash - dir) : 0, dir);
    if (parent[0] && folder_make(parent, made, 8, &n_made) != 0) {
        snprintf(err, errlen, "%s: cannot create the folder: %s", parent, strerror(errno));
        return -1;
    }
    int n = snprintf(tmp, len, "%.*s.celadon-museum-%ld-%u", slash ? (int)(slash - dir) + 1 : 0, dir,
                     (long)getpid(), atomic_fetch_add(&temp_counter, 1u));
    temp_files_hold();
    if (n >= 0 && (size_t)n < len)
        temp_files_track(tmp);
    int made_tmp = n >= 0 && (size_t)n < len && mkdir(tmp, 0777) == 0;
    if (!made_tmp)
        temp_files_forget(tmp);
    temp_files_release();
    if (!made_tmp) {
        snprintf(err, errlen, "%s: cannot create a folder beside it: %s", dir,
                 n < 0 || (size_t)n >= len ? "name too long" : strerror(errno));
        for (int k = n_made - 1; k >= 0; k--)
            rmdir(made[k]);
        return -1;
    }
    return 0;
}

static int remove_entry(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
    (void)st, (void)flag, (void)ftw;
    remove(path);
    return 0;
}

void museum_folder_remove(const char *dir)
{
    nftw(dir, remove_entry, 16, FTW_DEPTH | FTW_PHYS);
    temp_files_forget(dir);
}

/* The renames of museum_folder_publish; 0, or -1 with errno set. */
static int publish(const char *tmp, const char *dir)
{
    struct stat st;
    if (stat(dir, &st) != 0)
        return rename(tmp, dir);
    if (rmdir(dir) == 0) /* it was empty */
        return rename(tmp, dir);
    /* An old museum: moved aside, replaced, then deleted. */
    char old[PATH_MAX + 32];
    snprintf(old, sizeof old, "%s.old", tmp);
    if (rename(dir, old) != 0)
        return -1;
    if (rename(tmp, dir) == 0) {
        museum_folder_remove(old);
        return 0;
    }
    int saved = errno;
    rename(old, dir);
    errno = saved;
    return -1;
}

int museum_folder_publish(const char *tmp, const char *dir, char *err, size_t errlen)
{
    temp_files_hold();
    int rc = publish(tmp, dir);
    if (rc == 0)
        temp_files_forget(tmp);
    else
        snprintf(err, errlen, "cannot move the museum into %s: %s", dir, strerror(errno));
    temp_files_release();
    return rc;
}

int museum_folder_sub(const char *dir, const char *name)
{
    char path[PATH_MAX + 128], made[4][PATH_MAX];
    int n_made = 0;
    snprintf(path, sizeof path, "%s/%s", dir, name);
    return folder_make(path, made, 4, &n_made);
}
