/* museum.xml written with libxml2's text writer (which escapes the titles).
 * See museum_scene.h. */
#include "core/core.h"
#include "museum/museum_scene.h"

#include <errno.h>
#include <libxml/xmlwriter.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "museum/museum_gltf.h"

typedef xmlTextWriterPtr writer;

static void start(writer w, const char *tag) { xmlTextWriterStartElement(w, BAD_CAST tag); }
static void end(writer w) { xmlTextWriterEndElement(w); }
static void attr(writer w, const char *name, const char *value)
{
    xmlTextWriterWriteAttribute(w, BAD_CAST name, BAD_CAST value);
}

/* <TAG name="NAME" value="VALUE"/> */
static void prop(writer w, const char *tag, const char *name, const char *value)
{
    start(w, tag);
    attr(w, "name", name);
    attr(w, "value", value);
    end(w);
}

static void propf(writer w, const char *tag, const char *name, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
static void propf(writer w, const char *tag, const char *name, const char *fmt, ...)
{
    char buf[256];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    prop(w, tag, name, buf);
}

static void object(writer w, const char *tag, const char *type, const char *id)
{
    start(w, tag);
    attr(w, "type", type);
    if (id)
        attr(w, "id", id);
}

static void ref(writer w, const char *id)
{
    start(w, "ref");
    attr(w, "id", id);
    end(w);
}

static void diffuse(writer w, const char *id, double r, double g, double b)
{
    object(w, "bsdf", "diffuse", id);
    propf(w, "rgb", "reflectance", "%.4g, %.4g, %.4g", r, g, b);
    end(w);
}

/* A rectangle spanning corner + [0,1] du + [0,1] dv, normal du x dv: the
 * canonical [-1,1]^2 mapped by the affine matrix (du/2, dv/2, n, centre). */
static void rectangle(writer w, vec3 corner, vec3 du, vec3 dv, const char *bsdf, const char *name)
{
    vec3 n = v3_norm(v3_cross(du, dv));
    vec3 c = v3_add(corner, v3_scale(v3_add(du, dv), 0.5));
    object(w, "shape", "rectangle", NULL);
    if (name)
        attr(w, "name", name);
    start(w, "transform");
    attr(w, "name", "to_world");
    char m[512];
    snprintf(m, sizeof m, "%.6g %.6g %.6g %.6g  %.6g %.6g %.6g %.6g  %.6g %.6g %.6g %.6g  0 0 0 1", du.x / 2,
             dv.x / 2, n.x, c.x, du.y / 2, dv.y / 2, n.y, c.y, du.z / 2, dv.z / 2, n.z, c.z);
    start(w, "matrix");
    attr(w, "value", m);
    end(w);
    end(w);
    if (bsdf)
        ref(w, bsdf);
}

static void point_light(writer w, vec3 at, double intensity)
{
    object(w, "emitter", "point", NULL);
    propf(w, "point", "position", "%.6g, %.6g, %.6g", at.x, at.y, at.z);
    propf(w, "rgb", "intensity", "%.6g, %.6g, %.6g", intensity * MUSEUM_LIGHT_COLOR_R,
          intensity * MUSEUM_LIGHT_COLOR_G, intensity * MUSEUM_LIGHT_COLOR_B);
    end(w);
}

static void camera(writer w, const layout_t *l)
{
    object(w, "sensor", "perspective", NULL);
    prop(w, "string", "fov_axis", "y");
    propf(w, "float", "fov", "%.6g", l->camera_yfov_deg);
    start(w, "transform");
    attr(w, "name", "to_world");
    start(w, "lookat");
    char buf[128];
    vec3 o = l->camera_position, t = l->camera_target;
    snprintf(buf, sizeof buf, "%.6g, %.6g, %.6g", o.x, o.y, o.z);
    attr(w, "origin", buf);
    snprintf(buf, sizeof buf, "%.6g, %.6g, %.6g", t.x, t.y, t.z);
    attr(w, "target", buf);
    attr(w, "up", "0, 1, 0");
    end(w);
    end(w);
    object(w, "sampler", "zsobol", NULL);
    prop(w, "integer", "sample_count", "$spp");
    end(w);
    object(w, "film", "hdrfilm", NULL);
    prop(w, "integer", "width", "$resx");
    prop(w, "integer", "height", "$resy");
    end(w);
    end(w);
}

static void room(writer w, const layout_t *l)
{
    double x = l->width / 2, z = l->depth / 2, h = l->height;
    rectangle(w, v3(-x, 0, z), v3(2 * x, 0, 0), v3(0, 0, -2 * z), "floor", "Floor");
    end(w);
    rectangle(w, v3(-x, h, -z), v3(2 * x, 0, 0), v3(0, 0, 2 * z), "ceiling", "Ceiling");
    end(w);
    rectangle(w, v3(-x, 0, -z), v3(2 * x, 0, 0), v3(0, h, 0), "wall", "Back wall");
    end(w);
    rectangle(w, v3(x, 0, z), v3(-2 * x, 0, 0), v3(0, h, 0), "wall", "Entrance wall");
    end(w);
    rectangle(w, v3(-x, 0, z), v3(0, 0, -2 * z), v3(0, h, 0), "wall", "Left wall");
    end(w);
    rectangle(w, v3(x, 0, -z), v3(0, 0, 2 * z), v3(0, h, 0), "wall", "Right wall");
    end(w);
    for (int k = 0; k < l->n_ceiling_lights; k++)
        point_light(w, l->ceiling_lights[k], MUSEUM_CEILING_LIGHT);
}

static void vessel(writer w, const museum_exhibit *e, const layout_exhibit *le)
{
    char buf[512];
    object(w, "shape", "sor", NULL);
    snprintf(buf, sizeof buf, "Vessel: %s", e->title);
    attr(w, "name", buf);
    snprintf(buf, sizeof buf, "vessels/%s/profile.json", e->slug);
    prop(w, "string", "filename", buf);
    propf(w, "float", "height", "%.6g", e->rim_height_m);
    prop(w, "boolean", "caps", "false");
    start(w, "transform");
    attr(w, "name", "to_world");
    start(w, "translate");
    snprintf(buf, sizeof buf, "%.6g, %.6g, %.6g", le->vessel_base.x, le->vessel_base.y, le->vessel_base.z);
    attr(w, "value", buf);
    end(w);
    end(w);
    object(w, "bsdf", "plastic", NULL);
    object(w, "texture", "bitmap", NULL);
    attr(w, "name", "diffuse_reflectance");
    snprintf(buf, sizeof buf, "vessels/%s/texture.png", e->slug);
    prop(w, "string", "filename", buf);
    end(w);
    prop(w, "float", "int_ior", "1.5");
    end(w);
    end(w);
}

/* A plate facing +z centred at c, its image (a file of the folder) diffuse on it. */
static void plate(writer w, const char *name, vec3 c, double width, double height, const char *image)
{
    rectangle(w, v3(c.x - width / 2, c.y - height / 2, c.z), v3(width, 0, 0), v3(0, height, 0), NULL, name);
    object(w, "bsdf", "diffuse", NULL);
    object(w, "texture", "bitmap", NULL);
    attr(w, "name", "reflectance");
    prop(w, "string", "filename", image);
    /* The rectangle's v runs up; the image's rows run down. */
    start(w, "transform");
    attr(w, "name", "to_uv");
    start(w, "scale");
    attr(w, "value", "1, -1, 1");
    end(w);
    start(w, "translate");
    attr(w, "value", "0, 1, 0");
    end(w);
    end(w);
    end(w);
    end(w);
    end(w);
}

/* Pedestal (a cube), the glass case's five faces, the label and the title
 * sign, the case light. */
static void exhibit(writer w, const museum_exhibit *e, const layout_exhibit *le)
{
    char buf[512];
    double hw = le->width / 2, p = le->pedestal_height, top = p + le->case_height;
    vec3 c = le->centre;
    object(w, "shape", "cube", NULL);
    snprintf(buf, sizeof buf, "Pedestal: %s", e->title);
    attr(w, "name", buf);
    start(w, "transform");
    attr(w, "name", "to_world");
    start(w, "scale");
    snprintf(buf, sizeof buf, "%.6g, %.6g, %.6g", hw, p / 2, hw);
    attr(w, "value", buf);
    end(w);
    start(w, "translate");
    snprintf(buf, sizeof buf, "%.6g, %.6g, %.6g", c.x, p / 2, c.z);
    attr(w, "value", buf);
    end(w);
    end(w);
    ref(w, "pedestal");
    end(w);

    snprintf(buf, sizeof buf, "Glass case: %s", e->title);
    double h = le->case_height;
    rectangle(w, v3(c.x - hw, p, c.z + hw), v3(2 * hw, 0, 0), v3(0, h, 0), "glass", buf);
    end(w);
    rectangle(w, v3(c.x + hw, p, c.z - hw), v3(-2 * hw, 0, 0), v3(0, h, 0), "glass", buf);
    end(w);
    rectangle(w, v3(c.x + hw, p, c.z + hw), v3(0, 0, -2 * hw), v3(0, h, 0), "glass", buf);
    end(w);
    rectangle(w, v3(c.x - hw, p, c.z - hw), v3(0, 0, 2 * hw), v3(0, h, 0), "glass", buf);
    end(w);
    rectangle(w, v3(c.x - hw, top, c.z + hw), v3(2 * hw, 0, 0), v3(0, 0, -2 * hw), "glass", buf);
    end(w);

    snprintf(buf, sizeof buf, "Label: %s", e->title);
    char file[256];
    snprintf(file, sizeof file, "labels/%s.png", e->slug);
    plate(w, buf, le->label_centre, le->label_width, le->label_height, file);
    if (le->sign_lines > 0) {
        snprintf(buf, sizeof buf, "Sign: %s", e->title);
        snprintf(file, sizeof file, "labels/%s-sign.png", e->slug);
        plate(w, buf, le->sign_centre, le->sign_width, le->sign_height, file);
    }
    point_light(w, le->light, museum_case_light(le));
}

static int write_document(writer w, const char *title, const layout_t *l, const museum_exhibit *ex, int n,
                          int with_vessels, int width, int height, int spp)
{
    char buf[512];
    if (xmlTextWriterStartDocument(w, NULL, "utf-8", NULL) < 0)
        return -1;
    xmlTextWriterSetIndent(w, 1);
    xmlTextWriterSetIndentString(w, BAD_CAST "    ");
    snprintf(buf, sizeof buf,
             " %s: the museum of museum.glb for `celadon render museum.xml -o OUT.png` (docs/museum.md). ", title);
    for (char *p = strstr(buf, "--"); p; p = strstr(p, "--")) /* "--" may not appear in a comment */
        p[1] = '=';
    xmlTextWriterWriteComment(w, BAD_CAST buf);
    start(w, "scene");
    attr(w, "version", "3.0.0");
    const char *names[3] = {"spp", "resx", "resy"};
    const int values[3] = {spp, width, height};
    for (int k = 0; k < 3; k++) {
        start(w, "default");
        attr(w, "name", names[k]);
        snprintf(buf, sizeof buf, "%d", values[k]);
        attr(w, "value", buf);
        end(w);
    }
    object(w, "integrator", "path", NULL);
    prop(w, "integer", "max_depth", "8");
    end(w);
    camera(w, l);
    diffuse(w, "floor", MUSEUM_FLOOR_RGB);
    diffuse(w, "wall", MUSEUM_WALL_RGB);
    diffuse(w, "ceiling", MUSEUM_CEILING_RGB);
    diffuse(w, "pedestal", 0.9, 0.89, 0.86);
    object(w, "bsdf", "thindielectric", "glass");
    prop(w, "float", "int_ior", "1.5");
    end(w);
    room(w, l);
    for (int i = 0; i < n; i++) {
        if (with_vessels)
            vessel(w, &ex[i], &l->exhibits[i]);
        exhibit(w, &ex[i], &l->exhibits[i]);
    }
    end(w);
    return xmlTextWriterEndDocument(w) < 0 ? -1 : 0;
}

int museum_scene_write(const char *path, const char *title, const layout_t *layout, const museum_exhibit *ex,
                       int n, int with_vessels, int width, int height, int spp, char *err, size_t errlen)
{
    char tmp[4200];
    atomic_temp_name(path, tmp, sizeof tmp);
    writer w = xmlNewTextWriterFilename(tmp, 0);
    if (!w) {
        snprintf(err, errlen, "cannot write %s", path);
        return -1;
    }
    int rc = write_document(w, title, layout, ex, n, with_vessels, width, height, spp);
    xmlFreeTextWriter(w);
    if (rc != 0 || rename(tmp, path) != 0) {
        snprintf(err, errlen, "cannot write %s: %s", path, rc ? "XML writer failed" : strerror(errno));
        remove(tmp);
        rc = -1;
    }
    atomic_temp_done(tmp);
    return rc;
}
