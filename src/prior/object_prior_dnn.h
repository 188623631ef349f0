/* The network runtime under the object prior (prior.h): OpenCV's DNN
 * module, behind a C API (object_prior_dnn.cpp). */
#ifndef CELADON_PRIOR_OBJECT_PRIOR_DNN_H
#define CELADON_PRIOR_OBJECT_PRIOR_DNN_H

#include <stddef.h>

typedef struct object_prior_net object_prior_net;

/* Loads an ONNX network; threads: OpenCV's worker threads. NULL with a
 * one-line reason in err when the file is no network OpenCV can run. */
object_prior_net *object_prior_net_load(const char *path, int threads, char *err, size_t len);
/* Runs it on one 1 x 3 x side x side blob (chw, planar); out: its one
 * side x side output map. Returns 0, or -1 with the reason in err. */
int object_prior_net_forward(object_prior_net *n, const float *chw, int side, float *out, char *err, size_t len);
void object_prior_net_free(object_prior_net *n);

#endif
