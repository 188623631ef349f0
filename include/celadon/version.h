/* celadon's version: the command's --version, every image's metadata, the
 * library's pkg-config file (celadon.pc) and the Python package's
 * __version__. */
#ifndef CELADON_VERSION_H
#define CELADON_VERSION_H

#define CELADON_VERSION "0.1.0"

/* CELADON_VERSION as the library was built with it. */
const char *celadon_version(void);

#endif
