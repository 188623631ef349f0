/* Temporaries a signal must not leave behind: every temporary output file
 * and folder is tracked from its naming until it is renamed into place or
 * removed. SIGINT, SIGTERM and SIGHUP (once temp_files_install has run)
 * remove what is tracked, then end the process by the same signal, so the
 * shell reports 128 + N (130 for Ctrl-C). A command that handles SIGINT
 * itself (render's Ctrl-C: the image so far) restores the previous handler
 * when done. Every change to the file system that makes or moves a
 * temporary (a temporary from its naming until it is renamed or removed, a
 * temporary folder's creation, moves into place of several renames) is a
 * hold: a signal waits for the holds under way in every thread to end and
 * lets no new one begin before it removes the temporaries, so no thread
 * can make one behind its back (docs/faults.md). */
#ifndef CELADON_CORE_TEMP_FILES_H
#define CELADON_CORE_TEMP_FILES_H

/* How many temporaries can be tracked at once; beyond that a temporary is
 * not tracked (the outputs stay correct, a signal may leave it). */
#define TEMP_FILES_MAX 64

/* Installs the handlers (main, once). */
void temp_files_install(void);

/* Tracks path (a file, or a folder whose files it removes with it) until
 * temp_files_forget(path). */
void temp_files_track(const char *path);
void temp_files_forget(const char *path);

/* Around a change to the file system: a signal that comes meanwhile is
 * acted on at its end. Holds nest; the three signals are blocked in the
 * calling thread until its outermost hold ends. */
void temp_files_hold(void);
void temp_files_release(void);

#endif
