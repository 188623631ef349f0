/* The network runtime under the object prior (prior.h): OpenCV's DNN
 * module behind a C table (object_prior_dnn.cpp), built as its own shared
 * object (libceladon-prior.so) and loaded by the first photo that needs the
 * network (core/backend_library.h): OpenCV's DNN and its libraries would
 * otherwise cost every process their loading at start. */
#ifndef CELADON_PRIOR_OBJECT_PRIOR_DNN_H
#define CELADON_PRIOR_OBJECT_PRIOR_DNN_H

#include <stddef.h>

typedef struct object_prior_net object_prior_net;

typedef struct {
    /* Loads an ONNX network; threads: OpenCV's worker threads. NULL with a
     * one-line reason in err when the file is no network OpenCV can run. */
    object_prior_net *(*load)(const char *path, int threads, char *err, size_t len);
    /* Runs it on one 1 x 3 x side x side blob (chw, planar); out: its one
     * side x side output map. Returns 0, or -1 with the reason in err. */
    int (*forward)(object_prior_net *n, const float *chw, int side, float *out, char *err, size_t len);
    void (*free)(object_prior_net *n);
} object_prior_dnn;

/* The symbol the shared object exports. */
#define OBJECT_PRIOR_DNN_SYMBOL "celadon_object_prior_dnn"

#endif
