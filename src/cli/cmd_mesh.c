/* celadon mesh: a saved profile revolved into a triangle mesh file. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

#include "celadon/mesh.h"
#include "celadon/profile.h"
#include "cli/cli_args.h"
#include "cli/commands.h"

static void usage(FILE *f)
{
    fprintf(f, "usage: celadon mesh PROFILE.json -o OUT.{obj,ply} [--segments N] [--height H] [--mouth-cap]\n"
               "                    [--up y|z]\n\n"
               "Revolves the profile's B-spline into a triangle mesh: one ring per curvature\n"
               "domain of the profile, N angular segments, the rim at height H (Y up, base at 0),\n"
               "texture coordinates as in the texture the reconstruction wrote. The base is\n"
               "capped; --mouth-cap closes the mouth too.\n\n"
               "  -o OUT          .obj (with OUT.mtl referencing texture.png when one sits\n"
               "                  beside the profile) or .ply (binary, with normals and uv)\n"
               "  --segments N    angular segments, 3 to 1000000 (default 360)\n"
               "  --height H      rim height in scene units (default 1)\n"
               "  --mouth-cap     add a disc closing the mouth\n"
               "  --up y|z        the axis of the vessel: y (default; Mitsuba, glTF, most viewers)\n"
               "                  or z (Blender, 3ds Max): the front then faces -y\n");
}

/* The folder part of path with a trailing slash ("" for a bare name). */
static void folder_of(const char *path, char *out, size_t len)
{
    const char *slash = strrchr(path, '/');
    snprintf(out, len, "%.*s", slash ? (int)(slash - path + 1) : 0, path);
}

static const char *extension(const char *path)
{
    const char *slash = strrchr(path, '/'), *dot = strrchr(path, '.');
    return dot && (!slash || dot > slash) ? dot : "";
}

/* The path of file relative to the folder dir, both canonical absolute
 * paths: "texture.png", "../photos/texture.png". */
static void relative_path(const char *dir, const char *file, char *out, size_t len)
{
    size_t i = 0, dl = strlen(dir);
    while (dir[i] && dir[i] == file[i])
        i++;
    size_t common; /* where file's part below the shared folders starts */
    if (dir[i] == '\0' && file[i] == '/')
        common = i + 1; /* dir holds file */
    else {
        while (i > 0 && file[i - 1] != '/')
            i--;
        common = i;
    }
    out[0] = '\0';
    const char *rest = common < dl ? dir + common : ""; /* dir's folders below the shared ones */
    for (const char *p = rest; *rest && p; p = strchr(p + 1, '/'))
        strncat(out, "../", len - strlen(out) - 1);
    strncat(out, file + common, len - strlen(out) - 1);
}

/* Writes OUT.mtl next to the OBJ when the profile has a texture.png beside
 * it; fills mtl_name (for mtllib) and mtl_path, or leaves them empty. The
 * material names the texture relative to the OBJ, so the two can move
 * together. Returns 0, or -1 after telling the user why the material was not
 * written. */
static int write_material(const char *profile_path, const char *out, char *mtl_name, char *mtl_path, size_t len)
{
    char tex_dir[4096], out_dir[4096], tex[4200], tex_ref[4200];
    mtl_name[0] = mtl_path[0] = '\0';
    folder_of(profile_path, tex_dir, sizeof tex_dir);
    snprintf(tex, sizeof tex, "%stexture.png", tex_dir);
    if (access(tex, R_OK) != 0)
        return 0;
    folder_of(out, out_dir, sizeof out_dir);
    char *abs = realpath(tex, NULL), *abs_out_dir = realpath(out_dir[0] ? out_dir : ".", NULL);
    if (abs && abs_out_dir)
        relative_path(abs_out_dir, abs, tex_ref, sizeof tex_ref);
    else
        snprintf(tex_ref, sizeof tex_ref, "%s", tex);
    free(abs);
    free(abs_out_dir);

    const char *ext = extension(out);
    const char *base = strrchr(out, '/') ? strrchr(out, '/') + 1 : out;
    snprintf(mtl_path, len, "%.*s.mtl", (int)(ext - out), out);
    snprintf(mtl_name, len, "%.*s.mtl", (int)(ext - base), base);
    char err[4400];
    if (mesh_write_mtl(mtl_path, tex_ref, err, sizeof err) != 0) {
        fprintf(stderr, "celadon: %s\n", err);
        return -1;
    }
    return 0;
}

int cmd_mesh(int argc, char **argv)
{
    const char *profile_path = NULL, *out = NULL;
    long segments = 360;
    double height = 1.0;
    int mouth_cap = 0, z_up = 0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        char *end;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            usage(stdout);
            return 0;
        } else if (!strcmp(a, "-o") || !strcmp(a, "--segments") || !strcmp(a, "--height") || !strcmp(a, "--up")) {
            if (i + 1 >= argc)
                return cli_usage_error("mesh", "%s needs a value", a);
            const char *v = argv[++i];
            if (!strcmp(a, "-o"))
                out = v;
            else if (!strcmp(a, "--up")) {
                if (strcmp(v, "y") && strcmp(v, "z"))
                    return cli_usage_error("mesh", "--up must be y or z, not '%s'", v);
                z_up = !strcmp(v, "z");
            }
            else if (!strcmp(a, "--segments")) {
                errno = 0;
                segments = strtol(v, &end, 10);
                if (errno || end == v || *end || segments < 3 || segments > 1000000)
                    return cli_usage_error("mesh", "--segments must be an integer from 3 to 1000000, not '%s'", v);
            } else {
                errno = 0;
                height = strtod(v, &end);
                if (errno || end == v || *end || !(height > 0.0) || height > 1e30)
                    return cli_usage_error("mesh", "--height must be a positive number, not '%s'", v);
            }
        } else if (!strcmp(a, "--mouth-cap"))
            mouth_cap = 1;
        else if (a[0] == '-' && a[1])
            return cli_usage_error("mesh", "unknown option '%s'", a);
        else if (profile_path)
            return cli_usage_error("mesh", "one profile at a time ('%s' is extra)", a);
        else
            profile_path = a;
    }
    if (!profile_path)
        return cli_usage_error("mesh", "%s", "missing PROFILE.json");
    if (!out)
        return cli_usage_error("mesh", "%s", "missing -o OUT.obj or -o OUT.ply");
    int ply = !strcasecmp(extension(out), ".ply");
    if (!ply && strcasecmp(extension(out), ".obj")) {
        fprintf(stderr, "celadon: %s: unknown mesh format (use .obj or .ply)\n", out);
        return 2;
    }

    profile_t p;
    char err[4400];
    if (profile_read_json(profile_path, &p, err, sizeof err) != 0) {
        fprintf(stderr, "celadon: %s: %s\n", profile_path, err);
        return 2;
    }
    mesh_t m;
    unsigned caps = MESH_CAP_BASE | (mouth_cap ? MESH_CAP_MOUTH : 0u);
    if (mesh_revolve(&p.curve, p.domains, p.n_domains, height, (int)segments, caps, &m) != 0) {
        fprintf(stderr, "celadon: %s: cannot revolve this profile at %ld segments (rim not above the base, "
                        "or too many vertices)\n", profile_path, segments);
        profile_free(&p);
        return 2;
    }
    profile_free(&p);
    if (z_up)
        mesh_to_z_up(&m);

    int rc;
    char mtl_name[4200] = "", mtl_path[4200] = "";
    if (ply)
        rc = mesh_write_ply(out, &m, err, sizeof err);
    else if (write_material(profile_path, out, mtl_name, mtl_path, sizeof mtl_path) != 0) {
        mesh_free(&m);
        return 2;
    } else if ((rc = mesh_write_obj(out, &m, mtl_name[0] ? mtl_name : NULL, err, sizeof err)) != 0 && mtl_path[0])
        remove(mtl_path); /* nothing half-written stays behind */
    if (rc != 0) {
        fprintf(stderr, "celadon: %s\n", err);
        mesh_free(&m);
        return 2;
    }
    printf("%s: %d vertices, %d triangles%s%s\n", out, m.n_verts, m.n_tris, !ply && mtl_name[0] ? ", material " : "",
           !ply && mtl_name[0] ? mtl_path : "");
    mesh_free(&m);
    return 0;
}
