"""The C library (libceladon.so) through ctypes: where it is found, the
prototypes of the functions the package calls, and the failures they report.

ctypes releases the GIL for the duration of every call into the library, so
renders and reconstructions run while other Python threads go on."""
import ctypes
import os
import threading

_HERE = os.path.dirname(os.path.abspath(__file__))


class Error(RuntimeError):
    """A failure the CLI reports with exit status 1 (out of memory, cannot write)."""


class InputError(Error, ValueError):
    """Bad input, the CLI's exit status 2: str() is the line the CLI prints after 'celadon: '."""


def _candidates():
    """Where the library may be, in order: $CELADON_LIBRARY, the build tree
    (python/celadon -> build/libceladon.so), the LIBDIR `make install` recorded,
    then the dynamic loader's own search (LD_LIBRARY_PATH, ld.so.cache)."""
    env = os.environ.get("CELADON_LIBRARY")
    if env:
        yield env
    yield os.path.join(_HERE, "..", "..", "build", "libceladon.so")
    try:
        from celadon._installed import LIBRARY
        yield LIBRARY
    except ImportError:
        pass
    yield "libceladon.so.0"


def _load():
    tried = []
    for path in _candidates():
        if os.sep in path and not os.path.exists(path):
            tried.append(path)
            continue
        try:
            return ctypes.CDLL(path), os.path.abspath(path) if os.sep in path else path
        except OSError as e:
            tried.append(f"{path} ({e})")
    raise ImportError("celadon: libceladon.so not found (make python builds it; tried "
                      + ", ".join(tried) + ")")


lib, path = _load()

c_int, c_double, c_char_p, c_void_p = ctypes.c_int, ctypes.c_double, ctypes.c_char_p, ctypes.c_void_p
c_intp, c_doublep = ctypes.POINTER(c_int), ctypes.POINTER(c_double)
ERR_LEN = 2048


class SceneDefine(ctypes.Structure):
    """scene_define (scene_xml.h): one -D name=value."""
    _fields_ = [("name", c_char_p), ("value", c_char_p), ("fallback", ctypes.c_bool)]


class RenderImageOptions(ctypes.Structure):
    """render_image_options (render_image.h)."""
    _fields_ = [("width", c_int), ("height", c_int), ("spp", c_int), ("seed", ctypes.c_longlong),
                ("mesh_segments", c_int), ("threads", c_int), ("aovs", ctypes.c_uint)]


class RenderStats(ctypes.Structure):
    """The leading fields of render_stats (render.h), the ones read here."""
    _fields_ = [("seconds", c_double), ("samples", ctypes.c_uint64), ("interrupted", c_int)]


class Image(ctypes.Structure):
    """image_t (image.h)."""
    _fields_ = [("width", c_int), ("height", c_int), ("channels", c_int), ("bits", c_int),
                ("has_alpha", c_int), ("data", ctypes.POINTER(ctypes.c_float))]


class Mesh(ctypes.Structure):
    """mesh_t (mesh.h)."""
    _fields_ = [("n_verts", c_int), ("n_tris", c_int), ("pos", ctypes.POINTER(ctypes.c_float)),
                ("nrm", ctypes.POINTER(ctypes.c_float)), ("uv", ctypes.POINTER(ctypes.c_float)),
                ("tri", ctypes.POINTER(ctypes.c_uint32))]


def _proto(name, restype, *argtypes):
    f = getattr(lib, name)
    f.restype, f.argtypes = restype, list(argtypes)
    return f


ERR = (c_char_p, ctypes.c_size_t)
celadon_version = _proto("celadon_version", c_char_p)
free = _proto("free", None, c_void_p)
scene_create_from_file = _proto("scene_create_from_file", c_void_p, c_char_p, ctypes.POINTER(SceneDefine), c_int,
                                c_void_p, *ERR)
scene_destroy = _proto("scene_destroy", None, c_void_p)
scene_film_size = _proto("scene_film_size", None, c_void_p, c_intp, c_intp)
scene_spp = _proto("scene_spp", c_int, c_void_p)
scene_seed = _proto("scene_seed", ctypes.c_uint64, c_void_p)
render_aov_parse = _proto("render_aov_parse", c_int, c_char_p, ctypes.POINTER(ctypes.c_uint))
render_request_stop = _proto("render_request_stop", None)
render_image_cancel_stop = _proto("render_image_cancel_stop", None)
render_image_create = _proto("render_image_create", c_void_p, c_char_p, ctypes.POINTER(SceneDefine), c_int,
                             ctypes.POINTER(RenderImageOptions), c_intp, *ERR)
render_image_destroy = _proto("render_image_destroy", None, c_void_p)
render_image_size = _proto("render_image_size", None, c_void_p, c_intp, c_intp, c_intp)
render_image_channel = _proto("render_image_channel", c_char_p, c_void_p, c_int)
render_image_pixels = _proto("render_image_pixels", ctypes.POINTER(ctypes.c_float), c_void_p)
render_image_stats = _proto("render_image_stats", ctypes.POINTER(RenderStats), c_void_p)
crosscheck_measure = _proto("crosscheck_measure", c_int, c_char_p, ctypes.POINTER(SceneDefine), c_int,
                            ctypes.POINTER(RenderImageOptions), c_intp, c_int, c_int, ctypes.POINTER(c_void_p), *ERR)
image_read = _proto("image_read", c_int, c_char_p, ctypes.POINTER(Image), *ERR)
image_free = _proto("image_free", None, ctypes.POINTER(Image))
reconstruction_create = _proto("reconstruction_create", c_void_p, c_char_p, ctypes.POINTER(Image),
                               ctypes.POINTER(c_char_p), ctypes.POINTER(c_char_p), c_int, c_intp, *ERR)
reconstruction_destroy = _proto("reconstruction_destroy", None, c_void_p)
reconstruction_profile_text = _proto("reconstruction_profile_text", c_void_p, c_void_p, c_char_p, *ERR)
reconstruction_radius = _proto("reconstruction_radius", c_int, c_void_p, c_double, c_doublep)
reconstruction_mesh = _proto("reconstruction_mesh", c_int, c_void_p, c_int, ctypes.c_uint, ctypes.POINTER(Mesh))
mesh_free = _proto("mesh_free", None, ctypes.POINTER(Mesh))


def err_buffer():
    """Each call gets its own buffer: failures of calls in several threads never mix."""
    return ctypes.create_string_buffer(ERR_LEN), ERR_LEN


def raise_for(status, err):
    """The exception of a failed call: InputError for status 2 (bad input), Error otherwise."""
    message = err.value.decode("utf-8", "replace")
    raise (InputError if status == 2 else Error)(message)


def take_text(ptr):
    """A malloc'd C string, copied and freed."""
    try:
        return ctypes.string_at(ptr).decode("utf-8")
    finally:
        free(ptr)


def defines(params):
    """-D name=value for each keyword parameter: an array of scene_define, and the
    bytes it points to (keep them alive as long as the array)."""
    keep = []
    arr = (SceneDefine * max(1, len(params)))()
    for i, (name, value) in enumerate(params.items()):
        if isinstance(value, bool):
            value = "true" if value else "false"
        keep += [str(name).encode(), str(value).encode()]
        arr[i] = SceneDefine(keep[-2], keep[-1], False)
    return arr, keep


def interruptible(work):
    """Runs work() (calls into the library that render) so that Ctrl-C stops it.

    In the main thread the work runs in a helper thread while this one waits;
    a KeyboardInterrupt asks the library to stop (render_request_stop, as the
    CLI's SIGINT handler does) until the work returns, then propagates. The
    stop is the process's: it stops renders of other threads too. Elsewhere
    (not the main thread, where no signal arrives) work() simply runs."""
    if threading.current_thread() is not threading.main_thread():
        return work()
    out = {}

    def run():
        try:
            out["value"] = work()
        except BaseException as e:  # handed to the waiting thread
            out["error"] = e

    t = threading.Thread(target=run, name="celadon-render", daemon=True)
    try:  # t.start() inside: a Ctrl-C while it waits for the thread to run stops the work too
        t.start()
        while t.is_alive():
            t.join(0.05)
    except KeyboardInterrupt:
        while t.is_alive():  # a crosscheck renders several times: stop each
            render_request_stop()
            try:
                t.join(0.01)
            except KeyboardInterrupt:  # a second Ctrl-C while it stops
                pass
        render_image_cancel_stop()
        raise
    if "error" in out:
        raise out["error"]
    return out["value"]
