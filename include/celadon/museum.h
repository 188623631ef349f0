/* The automatic museum: photographs of vessels in, a walkable museum out
 * (docs/museum.md). One call reconstructs every photo through the library
 * pipeline (reconstruct.h, in parallel), lays out a room with a pedestal, a
 * glass case, a light and a label per vessel, and writes into one folder:
 *
 *   museum.glb    binary glTF 2.0: the vessels at their real size with their
 *                 levels of detail, textures, the room, cases, lights, labels,
 *                 the entrance camera
 *   index.html, museum.js   the page that walks it (desktop and WebXR)
 *   museum.xml    the same museum as a scene for `celadon render` (every
 *                 vessel an exact `sor`), preview.png its path-traced view
 *                 from the entrance
 *   museum.json   what was built: the manifest of the folder, the figures
 *   probe.hdr     the room's light at the entrance, baked by the path tracer
 *   vessels/SLUG/profile.json, texture.png, probe.hdr (the light around it);
 *   labels/SLUG.png
 *
 * The folder appears whole or not at all; a folder that already holds a
 * museum (and nothing else) is replaced. Units are metres, Y up. */
#ifndef CELADON_MUSEUM_H
#define CELADON_MUSEUM_H

#include <stddef.h>

enum { MUSEUM_MAX_LODS = 8 };

/* The height a vessel is given when the catalogue gives neither its height
 * nor its diameter; its label then says "Height not recorded". */
#define MUSEUM_DEFAULT_HEIGHT_CM 30.0

typedef struct {
    const char *out_dir;
    const char *catalogue;   /* CSV (docs/museum.md), or NULL */
    const char *title;       /* the museum's name; NULL: "Celadon museum" */
    int lods[MUSEUM_MAX_LODS], n_lods; /* segments per level; n_lods = 0 chooses them by screen-space error */
    int preview_width, preview_height, preview_spp; /* preview_spp = 0: no preview.png */
    int bake_spp;            /* >= 1: samples per texel of the baked light (lightmaps and probes) */
    const char *web_dir;     /* the folder holding index.html and museum.js (built by make); NULL or
                                missing files: the page is left out and web_missing set */
    int progress;            /* 1: progress bar of the preview on a TTY */
    int force;               /* include vessels that fail the quality gate (reconstruct --force),
                                their labels and museum.json saying so */
} museum_options;

/* Defaults: no catalogue, LODs chosen automatically, a 640x360 preview at
 * 16 samples per pixel, the light baked at MUSEUM_DEFAULT_BAKE_SPP, no web
 * folder. */
#define MUSEUM_DEFAULT_BAKE_SPP 16
museum_options museum_options_default(void);

typedef struct {
    char photo[4096];        /* the photo's path */
    int status;              /* 0 in the museum, 2 refused (bad input), 1 internal failure */
    char error[512];         /* why not, one line without the file name */
    int below_gate;          /* with force: in the museum although it failed the quality gate
                                (error then says which figures) */
} museum_photo_report;

typedef struct {
    int n_photos, n_vessels;
    museum_photo_report *photos;   /* one per photo, in the order given */
    long long triangles_full;      /* every vessel at its finest level, plus the room, cases, labels */
    long long triangles_entrance;  /* with the levels seen from the entrance camera */
    long long triangles_coarsest;  /* every vessel at its coarsest level */
    int draw_calls;                /* meshes drawn per frame (one level per vessel) */
    long long glb_bytes;
    double room[3];                /* width, depth, height, m */
    double ms_reconstruct, ms_write, ms_bake, ms_preview, ms_total; /* wall clock; ms_write includes ms_bake */
    int web_missing;               /* index.html or museum.js was not found in web_dir */
} museum_report;

/* Builds the museum of photos[0..n) (with a catalogue, n may be 0: its rows
 * are the photos). Returns 0 when every photo is in the museum, 2 for bad
 * input (err: one line naming the file, when nothing was built: a bad
 * catalogue, an output folder that is not a museum, every photo refused;
 * otherwise the refused photos are in rep->photos), 1 for an internal
 * failure (err). rep is filled in either way; museum_report_free it. */
int museum_build(const char *const *photos, int n, const museum_options *opt, museum_report *rep, char *err,
                 size_t errlen);
void museum_report_free(museum_report *rep);

/* Serves the files under dir on 127.0.0.1:port (0: any free port) until
 * SIGINT or SIGTERM; GET and HEAD only, no listing, nothing outside dir.
 * Prints "celadon: serving DIR at http://127.0.0.1:PORT/" on stdout (and
 * flushes it) once it listens. Returns 0 after a signal, or -1 with a
 * reason when it cannot listen. */
int museum_serve(const char *dir, int port, char *err, size_t errlen);

#endif
