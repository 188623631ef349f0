#include <stdio.h>
#include <string.h>

#include "celadon/version.h"
#include "cli/commands.h"
#include "core/core.h"

static const cli_command commands[] = {
    {"reconstruct", "photo(s) of a vessel -> profile.json, texture, meshes, overlay", cmd_reconstruct},
    {"mesh", "profile.json -> triangle mesh (OBJ+MTL or PLY) at any resolution", cmd_mesh},
    {"render", "Mitsuba 3 scene -> image (EXR/PNG/JPEG) with the path tracer", cmd_render},
    {"merge", "the parts of a render (render --part K/N) -> its image", cmd_merge},
    {"denoise", "a render's EXR with its denoising, half, specular, variance AOVs -> denoised EXR", cmd_denoise},
    {"museum", "photos -> a walkable VR museum (glTF + WebXR page) and its path-traceable scene", cmd_museum},
    {"crosscheck", "analytic vs. meshed renders of a scene: errors against N, report and plot", cmd_crosscheck},
    {NULL, NULL, NULL},
};

static void usage(FILE *f)
{
    fprintf(f, "celadon " CELADON_VERSION " — one photograph of a vessel to an exact surface of revolution\n\n"
               "usage: celadon COMMAND [ARGS]   (celadon COMMAND --help for details)\n\ncommands:\n");
    for (const cli_command *c = commands; c->name; c++)
        fprintf(f, "  %-12s %s\n", c->name, c->summary);
}

int main(int argc, char **argv)
{
    temp_files_install(); /* a signal leaves no temporary behind */
    if (argc < 2) {
        usage(stderr);
        return 2;
    }
    if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h") || !strcmp(argv[1], "help")) {
        usage(stdout);
        return 0;
    }
    if (!strcmp(argv[1], "--version")) {
        printf("celadon %s\n", CELADON_VERSION);
        return 0;
    }
    for (const cli_command *c = commands; c->name; c++)
        if (!strcmp(argv[1], c->name))
            return c->run(argc - 1, argv + 1);
    fprintf(stderr, "celadon: unknown command '%s' (try celadon --help)\n", argv[1]);
    return 2;
}
