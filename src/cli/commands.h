/* Subcommands of the celadon CLI: each returns the process exit code
 * (0 ok, 1 internal failure, 2 bad input or usage). */
#ifndef CELADON_CLI_COMMANDS_H
#define CELADON_CLI_COMMANDS_H

typedef struct {
    const char *name;
    const char *summary;
    int (*run)(int argc, char **argv); /* argv[0] is the subcommand name */
} cli_command;

int cmd_mesh(int argc, char **argv);
int cmd_render(int argc, char **argv);
int cmd_crosscheck(int argc, char **argv);
int cmd_reconstruct(int argc, char **argv);
int cmd_museum(int argc, char **argv);
int cmd_merge(int argc, char **argv);
int cmd_denoise(int argc, char **argv);

#endif
