"""celadon from Python: numpy in and out over the C library (libceladon.so).

    import celadon
    profile = celadon.reconstruct("photo.png")           # -> Profile
    scene = celadon.load_scene("scene.xml", spp=16)       # -D spp=16
    image = scene.render(spp=4, res=(64, 48), seed=1)     # float32 (H, W, C), image.channels
    table = celadon.crosscheck(scene, segments=[16, 64, 256], spp=4)

Every computation is the library's; failures raise InputError (bad input:
the CLI's message) or Error. docs/python.md has the whole API."""
import ctypes
import json

import numpy as np

from celadon import _lib
from celadon._lib import Error, InputError

__all__ = ["__version__", "reconstruct", "load_scene", "crosscheck", "read_image", "library_path",
           "Profile", "Scene", "RenderedImage", "CrosscheckTable", "Error", "InputError"]

__version__ = _lib.celadon_version().decode()


def library_path():
    """The libceladon.so this package runs on."""
    return _lib.path


def read_image(path):
    """The image file at path (any format OpenImageIO reads: PNG, JPEG, EXR, ...)
    as float32 (H, W, C): the values the library's reader gives (8-bit sRGB
    stays sRGB, /255; an EXR's channels R, G, B, A first, then the others in
    the file's order). InputError "PATH: problem" when it cannot be read."""
    img = _lib.Image()
    err, n = _lib.err_buffer()
    if _lib.image_read(str(path).encode(), ctypes.byref(img), err, n) != 0:
        raise InputError(f"{path}: {err.value.decode('utf-8', 'replace')}")
    try:
        count = img.width * img.height * img.channels
        return np.ctypeslib.as_array(img.data, (count,)).reshape(img.height, img.width, img.channels).copy()
    finally:
        _lib.image_free(ctypes.byref(img))


def _image_struct(array):
    """An image_t over a float32 copy of array: (H, W) or (H, W, C) with C 1..4;
    integer arrays are scaled by their type's largest value (uint8 by 255)."""
    a = np.asarray(array)
    if a.ndim == 2:
        a = a[:, :, None]
    if a.ndim != 3 or not 1 <= a.shape[2] <= 4:
        raise ValueError(f"a photo is an (H, W) or (H, W, C) array with C from 1 to 4, not shape {a.shape}")
    bits = 32
    if np.issubdtype(a.dtype, np.integer):
        bits = 8 * a.dtype.itemsize
        a = a.astype(np.float32) / np.float32(np.iinfo(a.dtype).max)
    a = np.ascontiguousarray(a, dtype=np.float32)
    img = _lib.Image(a.shape[1], a.shape[0], a.shape[2], bits, int(a.shape[2] in (2, 4)),
                     a.ctypes.data_as(ctypes.POINTER(ctypes.c_float)))
    return img, a


class Profile:
    """A reconstructed vessel: its profile.json as attributes (bspline, axis,
    corners, camera, quality, ...), and what the profile gives (radius, mesh)."""

    def __init__(self, handle, source):
        self._handle = handle
        self.source = source
        err, n = _lib.err_buffer()
        text = _lib.reconstruction_profile_text(handle, source.encode(), err, n)
        if not text:
            _lib.raise_for(1, err)
        self._json = _lib.take_text(text)
        self.data = json.loads(self._json)
        for key in ("bspline", "axis", "corners", "camera", "meridian", "quality", "error_px", "side",
                    "domains", "excluded", "polyline"):
            setattr(self, key, self.data.get(key))

    def __del__(self):
        if getattr(self, "_handle", None):
            _lib.reconstruction_destroy(self._handle)
            self._handle = None

    def to_json(self):
        """profile.json's text, as `celadon reconstruct` writes it for the same photo and options."""
        return self._json

    def radius(self, h):
        """The radius at height h, both in units of the mesh revolved to height 1
        (base 0, rim 1): the outermost wall where several cross that height. A
        number for a number, an array for an array; NaN outside the profile."""
        out = np.empty(np.shape(h))
        r = ctypes.c_double()
        for i, hi in np.ndenumerate(np.asarray(h, dtype=float)):
            ok = _lib.reconstruction_radius(self._handle, float(hi), ctypes.byref(r)) == 0
            out[i] = r.value if ok else np.nan
        return float(out) if np.ndim(h) == 0 else out

    def mesh(self, segments=360, mouth_cap=False):
        """The revolved mesh of model.obj (height 1, Y up, base capped):
        (vertices float32 (V, 3), faces uint32 (F, 3), counter-clockwise from outside)."""
        m = _lib.Mesh()
        caps = 1 | (2 if mouth_cap else 0)  # MESH_CAP_BASE | MESH_CAP_MOUTH
        if int(segments) < 3 or _lib.reconstruction_mesh(self._handle, int(segments), caps, ctypes.byref(m)) != 0:
            raise ValueError(f"cannot revolve the profile into {segments} segments (at least 3)")
        try:
            v = np.ctypeslib.as_array(m.pos, (m.n_verts * 3,)).reshape(-1, 3).copy()
            f = np.ctypeslib.as_array(m.tri, (m.n_tris * 3,)).reshape(-1, 3).copy()
        finally:
            _lib.mesh_free(ctypes.byref(m))
        return v, f


def reconstruct(photo, threshold=None, side=None, segmenter=None, smoothing=None, fov=None, force=False):
    """The photo (a file path, or an (H, W[, C]) array: floats in [0, 1] or
    integers) reconstructed as `celadon reconstruct` does, with its options
    (--threshold, --side, --segmenter, --smoothing, --fov, --force): a Profile. A refused
    photo raises InputError with the CLI's message ("PHOTO: problem")."""
    opts = {"threshold": threshold, "side": side, "segmenter": segmenter, "smoothing": smoothing, "fov": fov,
            "force": "1" if force else None}
    names = [k.encode() for k, v in opts.items() if v is not None]
    values = [str(v).encode() for v in opts.values() if v is not None]
    c_names, c_values = (ctypes.c_char_p * max(1, len(names)))(*names), (ctypes.c_char_p * max(1, len(values)))(*values)
    if isinstance(photo, (str, bytes)) or hasattr(photo, "__fspath__"):
        source, path, img, keep = str(photo), str(photo).encode(), None, None
    else:
        source, path = "<array>", None
        img, keep = _image_struct(photo)
    status, (err, n) = ctypes.c_int(), _lib.err_buffer()
    handle = _lib.reconstruction_create(path, ctypes.byref(img) if img else None, c_names, c_values, len(names),
                                        ctypes.byref(status), err, n)
    del keep
    if not handle:
        message = err.value.decode("utf-8", "replace")
        raise (InputError if status.value == 2 else Error)(f"{source}: {message}")
    return Profile(handle, source)


class RenderedImage(np.ndarray):
    """A float32 (H, W, C) array with .channels (the EXR's channel names, e.g.
    ['R', 'G', 'B', 'Z']) and .seconds (the render's time)."""

    def __array_finalize__(self, obj):
        # A view that keeps the channel axis keeps the names; a slice of the
        # channels (image[..., :3]) has no names.
        names = getattr(obj, "channels", None)
        keep = names is not None and self.ndim == 3 and self.shape[2] == len(names)
        self.channels = names if keep else None
        self.seconds = getattr(obj, "seconds", None)

    def channel(self, name):
        """The (H, W) plane of the channel called name."""
        return np.asarray(self)[:, :, self.channels.index(name)]


def _render_options(spp=None, res=None, seed=None, geometry="analytic", aovs=(), threads=None):
    """render_image_options of `celadon render`'s overrides."""
    o = _lib.RenderImageOptions(0, 0, 0, -1, 0, 0, 0)
    if spp is not None:
        if not 1 <= int(spp) <= 1 << 24:
            raise ValueError(f"spp wants an integer from 1 to 16777216, not '{spp}'")
        o.spp = int(spp)
    if res is not None:
        w, h = (int(x) for x in (res.split("x") if isinstance(res, str) else res))
        if not (1 <= w <= 65536 and 1 <= h <= 65536):
            raise ValueError(f"res wants (W, H) with sizes from 1 to 65536, not {res!r}")
        o.width, o.height = w, h
    if seed is not None:
        if int(seed) < 0:
            raise ValueError(f"seed wants a non-negative integer, not '{seed}'")
        o.seed = int(seed)
    if geometry != "analytic":
        n = geometry[5:] if isinstance(geometry, str) and geometry.startswith("mesh:") else ""
        if not n.isdigit() or not 3 <= int(n) <= 1000000:
            raise ValueError(f"geometry wants analytic or mesh:N with N from 3 to 1000000, not '{geometry}'")
        o.mesh_segments = int(n)
    if aovs:
        mask = ctypes.c_uint()
        if _lib.render_aov_parse(",".join(aovs).encode(), ctypes.byref(mask)) != 0:
            raise ValueError(f"aovs wants a list of depth, normal, albedo, not {list(aovs)!r}")
        o.aovs = mask.value
    if threads is not None:
        o.threads = int(threads)
    return o


class Scene:
    """A Mitsuba 3 scene file with its -D parameters, checked by building it
    once (load_scene). Each render builds it again with its own overrides."""

    def __init__(self, path, params):
        self.path, self.params = str(path), dict(params)
        defs, keep = _lib.defines(self.params)
        err, n = _lib.err_buffer()
        handle = _lib.scene_create_from_file(self.path.encode(), defs, len(self.params), None, err, n)
        if not handle:
            _lib.raise_for(2, err)
        w, h = ctypes.c_int(), ctypes.c_int()
        _lib.scene_film_size(handle, ctypes.byref(w), ctypes.byref(h))
        self.size, self.spp, self.seed = (w.value, h.value), _lib.scene_spp(handle), _lib.scene_seed(handle)
        _lib.scene_destroy(handle)

    def __repr__(self):
        return f"Scene({self.path!r}, {self.params!r}: {self.size[0]}x{self.size[1]}, {self.spp} spp)"

    def render(self, spp=None, res=None, seed=None, geometry="analytic", aovs=(), threads=None):
        """The scene rendered as `celadon render SCENE -o OUT.exr` with these
        options (--spp, --res (W, H), --seed, --geometry analytic|mesh:N,
        --aov, --threads): a RenderedImage holding exactly the EXR's channels
        and values. Ctrl-C stops the render and raises KeyboardInterrupt."""
        opt = _render_options(spp, res, seed, geometry, aovs, threads)
        defs, keep = _lib.defines(self.params)

        def work():
            status, (err, n) = ctypes.c_int(), _lib.err_buffer()
            im = _lib.render_image_create(self.path.encode(), defs, len(self.params), ctypes.byref(opt),
                                          ctypes.byref(status), err, n)
            if not im:
                _lib.raise_for(status.value, err)
            try:
                w, h, c = ctypes.c_int(), ctypes.c_int(), ctypes.c_int()
                _lib.render_image_size(im, ctypes.byref(w), ctypes.byref(h), ctypes.byref(c))
                stats = _lib.render_image_stats(im).contents
                if stats.interrupted:
                    raise KeyboardInterrupt
                px = np.ctypeslib.as_array(_lib.render_image_pixels(im), (h.value * w.value * c.value,))
                out = px.reshape(h.value, w.value, c.value).copy().view(RenderedImage)
                out.channels = [_lib.render_image_channel(im, i).decode() for i in range(c.value)]
                out.seconds = stats.seconds
                return out
            finally:
                _lib.render_image_destroy(im)

        return _lib.interruptible(work)


def load_scene(path, **params):
    """The Mitsuba 3 scene at path with params as its -D name=value overrides
    (booleans as true/false). A bad scene raises InputError with the CLI's message."""
    return Scene(path, params)


class CrosscheckTable:
    """`celadon crosscheck`'s measurements: numpy columns segments, error
    (mean_abs_diff, the image error report.json fits), time (seconds of each
    meshed render), and every metric by name (rel_mse, coverage_area_px,
    depth_rel_err, normal_err_deg, ...); slope: report.json's fitted_slope;
    report: the whole report.json as a dict."""

    def __init__(self, report):
        self.report = report
        rows = report["segments"]
        self.columns = {k: np.array([np.nan if r[k] is None else r[k] for r in rows], dtype=float)
                        for k in rows[0] if k not in ("image", "png")} if rows else {}
        self.segments = self.columns["n"].astype(int)
        self.error = self.columns["mean_abs_diff"]
        self.time = self.columns["seconds"]
        self.slope = report["fitted_slope"]

    def __getitem__(self, metric):
        return self.columns[metric]

    def __len__(self):
        return len(self.segments)

    def __repr__(self):
        lines = [f"{'segments':>9} {'error':>12} {'time':>8}"]
        lines += [f"{n:9d} {e:12.6g} {t:8.3f}" for n, e, t in zip(self.segments, self.error, self.time)]
        return "\n".join(lines + [f"fitted slope {self.slope:.3f}"])


def crosscheck(scene, segments, spp=None, res=None, seed=None, fit_from=0, threads=None):
    """`celadon crosscheck` on a Scene (or a scene path) without its files: the
    scene rendered analytic and revolved into each N of segments with the
    same seed, measured: a CrosscheckTable. Ctrl-C stops it (KeyboardInterrupt)."""
    if not isinstance(scene, Scene):
        scene = load_scene(scene)
    opt = _render_options(spp, res, seed, threads=threads)
    segs = (ctypes.c_int * max(1, len(segments)))(*[int(n) for n in segments])
    defs, keep = _lib.defines(scene.params)

    def work():
        report, (err, n) = ctypes.c_void_p(), _lib.err_buffer()
        rc = _lib.crosscheck_measure(scene.path.encode(), defs, len(scene.params), ctypes.byref(opt), segs,
                                     len(segments), int(fit_from), ctypes.byref(report), err, n)
        if rc != 0:
            _lib.raise_for(2 if rc == -2 else 1, err)
        return json.loads(_lib.take_text(report.value))

    return CrosscheckTable(_lib.interruptible(work))
