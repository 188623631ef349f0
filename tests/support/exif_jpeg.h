/* Gives a JPEG file an EXIF block that holds one field, the 35 mm
 * equivalent focal length (FocalLengthIn35mmFilm, tag 0xA405), as a camera
 * writes it: an APP1 "Exif" segment right after the start-of-image marker,
 * a little-endian TIFF header, IFD0 with the pointer to the Exif IFD, and
 * the Exif IFD with the one SHORT. Written byte by byte here so that the
 * reader (OpenImageIO, src/image/oiio_shim.cpp) is tested against an
 * encoding it did not write itself. */
#ifndef CELADON_TESTS_EXIF_JPEG_H
#define CELADON_TESTS_EXIF_JPEG_H

/* Rewrites the JPEG at path in place. Returns 0, or -1 when the file
 * cannot be read or written or is no JPEG. */
int jpeg_add_exif_focal_35mm(const char *path, unsigned focal_mm);

#endif
