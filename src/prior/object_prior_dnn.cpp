// OpenCV's DNN module behind the extern "C" table of prior/object_prior_dnn.h:
// loads the salient-object network (ONNX) and runs it on one input blob.
// Built as its own shared object (libceladon-prior.so); it calls nothing of
// libceladon's.
extern "C" {
#include "prior/object_prior_dnn.h"
}

#include <opencv2/core.hpp>
#include <opencv2/dnn.hpp>

#include <cstdio>
#include <cstring>
#include <exception>
#include <string>

struct object_prior_net {
    cv::dnn::Net net;
};

static void set_err(char *err, size_t len, const char *what, const char *detail)
{
    if (!err || !len)
        return;
    std::string line = std::string(what) + (detail && *detail ? ": " : "") + (detail ? detail : "");
    for (char &c : line) // one line: OpenCV's messages span several
        if (c == '\n' || c == '\r')
            c = ' ';
    std::snprintf(err, len, "%s", line.c_str());
}

static object_prior_net *net_load(const char *path, int threads, char *err, size_t len)
{
    try {
        cv::setNumThreads(threads);
        object_prior_net *n = new object_prior_net;
        n->net = cv::dnn::readNetFromONNX(path);
        if (n->net.empty()) {
            delete n;
            set_err(err, len, "the network file holds no network", nullptr);
            return nullptr;
        }
        n->net.setPreferableBackend(cv::dnn::DNN_BACKEND_OPENCV);
        n->net.setPreferableTarget(cv::dnn::DNN_TARGET_CPU);
        return n;
    } catch (const std::exception &e) {
        set_err(err, len, "OpenCV could not read the network", e.what());
    } catch (...) {
        set_err(err, len, "OpenCV could not read the network", nullptr);
    }
    return nullptr;
}

static int net_forward(object_prior_net *n, const float *chw, int side, float *out, char *err, size_t len)
{
    try {
        int dims[4] = {1, 3, side, side};
        cv::Mat blob(4, dims, CV_32F, const_cast<float *>(chw));
        n->net.setInput(blob);
        cv::Mat y = n->net.forward();
        if (y.type() != CV_32F || y.total() != (size_t)side * side) {
            set_err(err, len, "the network's output is not one map of the input's size", nullptr);
            return -1;
        }
        std::memcpy(out, y.ptr<float>(), (size_t)side * side * sizeof *out);
        return 0;
    } catch (const std::exception &e) {
        set_err(err, len, "OpenCV failed running the network", e.what());
    } catch (...) {
        set_err(err, len, "OpenCV failed running the network", nullptr);
    }
    return -1;
}

static void net_free(object_prior_net *n) { delete n; }

extern "C" const object_prior_dnn celadon_object_prior_dnn = {net_load, net_forward, net_free};
