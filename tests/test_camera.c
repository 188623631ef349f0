/* The perspective camera: rays against the geometry of its frustum. */
#include <criterion/criterion.h>

#include "sensors/sensors.h"
#include "celadon/scene.h"

static double angle_deg(vec3 a, vec3 b)
{
    return acos(fmax(-1.0, fmin(1.0, v3_dot(v3_norm(a), v3_norm(b))))) * (180.0 / M_PI);
}

/* A camera at (1,2,3) looking toward (4,-1,7) with up roughly +y. */
static camera_t make(double fov, camera_fov_axis axis, int w, int h)
{
    transform4 l;
    cr_assert_eq(transform_lookat(v3(1, 2, 3), v3(4, -1, 7), v3(0, 1, 0), &l), 0);
    camera_t cam;
    char err[256];
    cr_assert_eq(camera_init(&cam, &l, fov, axis, w, h, 0.5, 50, err, sizeof err), 0, "%s", err);
    return cam;
}

Test(camera, centre_ray_follows_the_look_direction)
{
    camera_t cam = make(50, CAMERA_FOV_X, 64, 48);
    camera_ray_t r = camera_ray(&cam, 32, 24, 0.0, 0.0); /* the film's exact centre */
    vec3 look = v3_norm(v3(3, -3, 4));
    cr_assert_float_eq(v3_dot(r.ray.d, look), 1.0, 1e-15);
    cr_assert_float_eq(v3_len(r.ray.d), 1.0, 1e-15);
    cr_assert(r.ray.o.x == 1 && r.ray.o.y == 2 && r.ray.o.z == 3);
    cr_assert_float_eq(r.tmin, 0.5, 1e-15);
    cr_assert_float_eq(r.tmax, 50, 1e-13);
    /* An off-centre ray reaches the near plane at tmin (distance along look = near). */
    camera_ray_t c = camera_ray(&cam, 0, 0, 0.25, 0.75);
    cr_assert_float_eq(v3_dot(v3_scale(c.ray.d, c.tmin), look), 0.5, 1e-14);
    cr_assert_float_eq(v3_dot(v3_scale(c.ray.d, c.tmax), look), 50, 1e-12);
}

Test(camera, image_left_and_top_follow_the_lookat_frame)
{
    transform4 l;
    cr_assert_eq(transform_lookat(v3(0, 0, 5), v3(0, 0, 0), v3(0, 1, 0), &l), 0);
    camera_t cam;
    char err[256];
    cr_assert_eq(camera_init(&cam, &l, 60, CAMERA_FOV_X, 10, 10, 0.01, 100, err, sizeof err), 0);
    /* Looking down -z with +y up, the image's left is world -x and its top +y
     * (as in Mitsuba, where local +x = up x dir). */
    camera_ray_t left = camera_ray(&cam, 0, 5, 0, 0), top = camera_ray(&cam, 5, 0, 0, 0);
    cr_assert_lt(left.ray.d.x, -0.4);
    cr_assert_float_eq(left.ray.d.y, 0, 1e-15);
    cr_assert_gt(top.ray.d.y, 0.4);
    cr_assert_float_eq(top.ray.d.x, 0, 1e-15);
}

/* Angle between the rays through two film positions given in [0,1]^2. */
static double span(const camera_t *cam, double x0, double y0, double x1, double y1)
{
    camera_ray_t a = camera_ray(cam, 0, 0, x0 * cam->width, y0 * cam->height);
    camera_ray_t b = camera_ray(cam, 0, 0, x1 * cam->width, y1 * cam->height);
    return angle_deg(a.ray.d, b.ray.d);
}

Test(camera, fov_spans_the_requested_axis)
{
    const double fov = 70;
    /* Wide film 200x100 and tall film 100x200. */
    camera_t x = make(fov, CAMERA_FOV_X, 200, 100);
    cr_assert_float_eq(span(&x, 0, 0.5, 1, 0.5), fov, 1e-12);
    cr_assert_lt(span(&x, 0.5, 0, 0.5, 1), fov - 10);
    camera_t y = make(fov, CAMERA_FOV_Y, 200, 100);
    cr_assert_float_eq(span(&y, 0.5, 0, 0.5, 1), fov, 1e-12);
    camera_t d = make(fov, CAMERA_FOV_DIAGONAL, 200, 100);
    cr_assert_float_eq(span(&d, 0, 0, 1, 1), fov, 1e-12);
    cr_assert_float_eq(span(&d, 1, 0, 0, 1), fov, 1e-12);
    camera_t sw = make(fov, CAMERA_FOV_SMALLER, 200, 100), st = make(fov, CAMERA_FOV_SMALLER, 100, 200);
    cr_assert_float_eq(span(&sw, 0.5, 0, 0.5, 1), fov, 1e-12, "wide: the smaller side is y");
    cr_assert_float_eq(span(&st, 0, 0.5, 1, 0.5), fov, 1e-12, "tall: the smaller side is x");
    camera_t lw = make(fov, CAMERA_FOV_LARGER, 200, 100), lt = make(fov, CAMERA_FOV_LARGER, 100, 200);
    cr_assert_float_eq(span(&lw, 0, 0.5, 1, 0.5), fov, 1e-12);
    cr_assert_float_eq(span(&lt, 0.5, 0, 0.5, 1), fov, 1e-12);
    /* Square pixels: the image-plane extents keep the film's aspect ratio. */
    cr_assert_float_eq(x.tan_x / x.tan_y, 2.0, 1e-15);
    cr_assert_float_eq(d.tan_x / d.tan_y, 2.0, 1e-15);
}

Test(camera, from_sensor_and_bad_input)
{
    char err[512];
    const char *xml = "<scene version=\"3.0.0\">\n"
                      "  <sensor type=\"perspective\">\n"
                      "    <float name=\"fov\" value=\"30\"/><string name=\"fov_axis\" value=\"y\"/>\n"
                      "    <transform name=\"to_world\"><lookat origin=\"0 0 -3\" target=\"0 0 0\"/></transform>\n"
                      "  </sensor>\n"
                      "  <sensor type=\"perspective\" id=\"bad\"/>\n"
                      "</scene>\n";
    scene_desc *d =
        scene_desc_create_from_text(xml, strlen(xml), "mem.xml", NULL, 0, scene_plugin_find, err, sizeof err);
    cr_assert_null(d, "two sensors are refused");
    cr_assert_str_eq(err, "mem.xml:6: <scene> takes at most 1 <sensor>");
    const char *clip = "<scene version=\"3.0.0\">\n"
                       "  <sensor type=\"perspective\">\n"
                       "    <float name=\"fov\" value=\"30\"/><string name=\"fov_axis\" value=\"y\"/>\n"
                       "    <float name=\"near_clip\" value=\"2\"/><float name=\"far_clip\" value=\"1\"/>\n"
                       "  </sensor>\n"
                       "</scene>\n";
    d = scene_desc_create_from_text(clip, strlen(clip), "mem.xml", NULL, 0, scene_plugin_find, err, sizeof err);
    cr_assert_not_null(d, "%s", err);
    camera_t cam;
    const sensor_plugin *perspective = sensor_plugin_find("perspective");
    cr_assert_eq(perspective->create(scene_obj_child(scene_desc_root(d), SCENE_SENSOR), 10, 10, &cam, err, sizeof err),
                 -1);
    cr_assert_str_eq(err, "mem.xml:2: <sensor type=\"perspective\">: clip range [2, 1] needs 0 < near_clip < far_clip");
    scene_desc_destroy(d);

    const char *good = "<scene version=\"3.0.0\">\n"
                       "  <sensor type=\"perspective\">\n"
                       "    <float name=\"fov\" value=\"30\"/><string name=\"fov_axis\" value=\"y\"/>\n"
                       "    <transform name=\"to_world\"><lookat origin=\"0 0 -3\" target=\"0 0 0\"/></transform>\n"
                       "  </sensor>\n"
                       "</scene>\n";
    d = scene_desc_create_from_text(good, strlen(good), "mem.xml", NULL, 0, scene_plugin_find, err, sizeof err);
    cr_assert_not_null(d, "%s", err);
    scene_obj *s = scene_obj_child(scene_desc_root(d), SCENE_SENSOR);
    cr_assert_eq(perspective->create(s, 40, 20, &cam, err, sizeof err), 0, "%s", err);
    cr_assert_float_eq(span(&cam, 0.5, 0, 0.5, 1), 30, 1e-12);
    camera_ray_t c = camera_ray(&cam, 20, 10, 0, 0);
    cr_assert_float_eq(c.ray.d.z, 1, 1e-15, "lookat without up still looks at the target");
    cr_assert_float_eq(c.tmin, CAMERA_DEFAULT_NEAR_CLIP, 1e-15);
    char msg[256];
    cr_assert_eq(scene_obj_unconsumed(scene_desc_root(d), msg, sizeof msg), 0, "%s", msg);
    scene_desc_destroy(d);

    transform4 scaled = transform_scale(v3(2, 2, 2));
    cr_assert_eq(camera_init(&cam, &scaled, 40, CAMERA_FOV_X, 8, 8, 0.1, 10, err, sizeof err), -1);
    transform4 id = transform_identity();
    cr_assert_eq(camera_init(&cam, &id, 180, CAMERA_FOV_X, 8, 8, 0.1, 10, err, sizeof err), -1);
    cr_assert_eq(camera_init(&cam, &id, 40, CAMERA_FOV_X, 0, 8, 0.1, 10, err, sizeof err), -1);
    transform4 mirror = transform_scale(v3(-1, 1, 1));
    cr_assert_eq(camera_init(&cam, &mirror, 40, CAMERA_FOV_X, 8, 8, 0.1, 10, err, sizeof err), 0, "reflection is rigid");
}
