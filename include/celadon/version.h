/* celadon's version: `celadon --version` and every image's metadata. */
#ifndef CELADON_VERSION_H
#define CELADON_VERSION_H

#define CELADON_VERSION "0.1.0"

#endif
