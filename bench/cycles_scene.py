# celadon's bundled scenes rebuilt for Blender Cycles (Debian's Blender 3.4),
# for the noise-per-CPU-second comparison (bench/cycles_efficiency.py,
# docs/BENCHMARKS.md "Noise per CPU second"):
#
#   blender -b --factory-startup --python bench/cycles_scene.py -- \
#       SCENE SPP WxH OUT.exr SEED OBJDIR
#
# SCENE is studio, cornell-sor or showcase; OBJDIR holds NAME.obj for each of
# the scene's vessels (VESSELS in bench/cycles_efficiency.py: `celadon mesh`
# of its profile at the scene's height, 360 segments), the textures are the
# repository's. The same camera, lights, materials and path depth as the
# scene file, a 1-pixel box filter, no denoising, no adaptive sampling, no
# clamping, 2 threads. Mitsuba's frame (y up) becomes Blender's (z up) by
# (x, y, z) -> (x, -z, y): every Mitsuba to_world T is placed as
# matrix_world = Y_UP @ T, Blender's primitives sharing Mitsuba's local
# frames (a plane of size 2 is Mitsuba's rectangle [-1,1]^2 facing +z).
import math
import os
import sys

import bpy
from mathutils import Matrix, Vector

args = sys.argv[sys.argv.index("--") + 1:]
SCENE, SPP = args[0], int(args[1])
W, H = (int(v) for v in args[2].split("x"))
OUT, SEED, OBJDIR = args[3], int(args[4]), args[5]
SCENES = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "scenes")

Y_UP = Matrix(((1, 0, 0, 0), (0, 0, -1, 0), (0, 1, 0, 0), (0, 0, 0, 1)))


def translate(x=0.0, y=0.0, z=0.0):
    return Matrix.Translation(Vector((x, y, z)))


def rotate(axis, degrees):
    return Matrix.Rotation(math.radians(degrees), 4, axis)


def scale(x, y=None, z=None):
    return Matrix.Diagonal(Vector((x, x if y is None else y, x if z is None else z, 1.0)))


def lookat(origin, target, up):
    """Mitsuba's lookat: local z toward the target, x = up x z."""
    o, t, u = Vector(origin), Vector(target), Vector(up)
    d = (t - o).normalized()
    left = u.cross(d).normalized()
    m = Matrix.Identity(4)
    for i, column in enumerate((left, d.cross(left), d, o)):
        for r in range(3):
            m[r][i] = column[r]
    return m


def material(name):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    m.node_tree.nodes.clear()
    return m, m.node_tree, m.node_tree.nodes.new("ShaderNodeOutputMaterial")


def diffuse(name, rgb):
    m, tree, out = material(name)
    d = tree.nodes.new("ShaderNodeBsdfDiffuse")
    d.inputs["Color"].default_value = (*rgb, 1.0)
    d.inputs["Roughness"].default_value = 0.0
    tree.links.new(d.outputs[0], out.inputs[0])
    return m


def mix_into(tree, fac, a, b, out):
    """(1 - fac) a + fac b into the material's output (sockets)."""
    mix = tree.nodes.new("ShaderNodeMixShader")
    tree.links.new(fac, mix.inputs[0])
    tree.links.new(a, mix.inputs[1])
    tree.links.new(b, mix.inputs[2])
    tree.links.new(mix.outputs[0], out.inputs[0])


def front_only(tree, front, out):
    """front on the front side, black behind (Mitsuba's one-sided BSDFs;
    Cycles' are two-sided)."""
    black = tree.nodes.new("ShaderNodeBsdfDiffuse")
    black.inputs[0].default_value = (0.0, 0.0, 0.0, 1.0)
    geometry = tree.nodes.new("ShaderNodeNewGeometry")
    mix_into(tree, geometry.outputs["Backfacing"], front, black.outputs[0], out)


def plastic(name, rgb, alpha, ior, texture=None, one_sided=False):
    """Mitsuba's (rough)plastic as a Principled BSDF: the base under a GGX
    coat of reflectance ((ior - 1) / (ior + 1))^2 (Specular = F0 / 0.08),
    roughness sqrt(alpha); one_sided: black behind, as Mitsuba's (a vase's
    inside seen through its mouth)."""
    m, tree, out = material(name)
    p = tree.nodes.new("ShaderNodeBsdfPrincipled")
    p.distribution = "GGX"
    p.inputs["Base Color"].default_value = (*rgb, 1.0)
    p.inputs["Roughness"].default_value = math.sqrt(alpha)
    p.inputs["Specular"].default_value = ((ior - 1.0) / (ior + 1.0)) ** 2 / 0.08
    if texture:
        t = tree.nodes.new("ShaderNodeTexImage")
        t.image = bpy.data.images.load(texture)
        tree.links.new(t.outputs["Color"], p.inputs["Base Color"])
    if one_sided:
        front_only(tree, p.outputs[0], out)
    else:
        tree.links.new(p.outputs[0], out.inputs[0])
    return m


def fresnel_plastic(name, rgb, alpha, ior):
    """Mitsuba's roughplastic (Beckmann, its default) as Blender's classic
    plastic: a diffuse base and a Beckmann Glossy coat mixed by the
    dielectric Fresnel reflectance at the viewing angle. On the showcase's
    dark floor, whose radiance is largely the luminous ceiling's reflection,
    plastic()'s Principled BSDF (GGX, its coat added to an undimmed base)
    came out 11% brighter than celadon's floor (2.7% on the image's mean),
    this 5% (1.0%)."""
    m, tree, out = material(name)
    d = tree.nodes.new("ShaderNodeBsdfDiffuse")
    d.inputs["Color"].default_value = (*rgb, 1.0)
    d.inputs["Roughness"].default_value = 0.0
    g = tree.nodes.new("ShaderNodeBsdfGlossy")
    g.distribution = "BECKMANN"
    g.inputs["Roughness"].default_value = math.sqrt(alpha)  # Cycles squares it
    fresnel = tree.nodes.new("ShaderNodeFresnel")
    fresnel.inputs["IOR"].default_value = ior
    mix_into(tree, fresnel.outputs[0], d.outputs[0], g.outputs[0], out)
    return m


def gold(name, alpha):
    """Mitsuba's roughconductor "Au" as a metallic Principled BSDF whose base
    colour is gold's normal-incidence reflectance in linear sRGB (Cycles 3.4
    has no complex-IOR Fresnel), roughness sqrt(alpha). Only the showcase's
    thin case frames use it."""
    m, tree, out = material(name)
    p = tree.nodes.new("ShaderNodeBsdfPrincipled")
    p.distribution = "GGX"
    p.inputs["Base Color"].default_value = (1.0, 0.766, 0.336, 1.0)
    p.inputs["Metallic"].default_value = 1.0
    p.inputs["Roughness"].default_value = math.sqrt(alpha)
    tree.links.new(p.outputs[0], out.inputs[0])
    return m


def thin_glass(name, ior):
    """Mitsuba's thindielectric: a sheet reflecting R' = 2r / (1 + r) (r the
    dielectric Fresnel reflectance at the sheet's angle, the sheet's
    inter-reflections summed) and passing the rest straight through, as a mix
    of a sharp Glossy (no Fresnel of its own) and a Transparent BSDF, which
    Cycles' shadow rays cross with that weight, as celadon's do. Cycles'
    Fresnel node inverts the IOR on the back side; fed 1/ior there, it takes
    the air-to-glass r on both sides, as a thin sheet does."""
    m, tree, out = material(name)
    geometry = tree.nodes.new("ShaderNodeNewGeometry")
    eta = tree.nodes.new("ShaderNodeMixRGB")  # a scalar blend: ior in front, 1 / ior behind
    tree.links.new(geometry.outputs["Backfacing"], eta.inputs[0])
    eta.inputs[1].default_value = (ior, ior, ior, 1.0)
    eta.inputs[2].default_value = (1.0 / ior, 1.0 / ior, 1.0 / ior, 1.0)
    fresnel = tree.nodes.new("ShaderNodeFresnel")
    tree.links.new(eta.outputs[0], fresnel.inputs["IOR"])
    two_r = tree.nodes.new("ShaderNodeMath")
    two_r.operation = "MULTIPLY"
    tree.links.new(fresnel.outputs[0], two_r.inputs[0])
    two_r.inputs[1].default_value = 2.0
    one_plus_r = tree.nodes.new("ShaderNodeMath")
    one_plus_r.operation = "ADD"
    tree.links.new(fresnel.outputs[0], one_plus_r.inputs[0])
    one_plus_r.inputs[1].default_value = 1.0
    sheet_r = tree.nodes.new("ShaderNodeMath")
    sheet_r.operation = "DIVIDE"
    tree.links.new(two_r.outputs[0], sheet_r.inputs[0])
    tree.links.new(one_plus_r.outputs[0], sheet_r.inputs[1])
    transparent = tree.nodes.new("ShaderNodeBsdfTransparent")
    mirror = tree.nodes.new("ShaderNodeBsdfGlossy")
    mirror.distribution = "SHARP"
    mix_into(tree, sheet_r.outputs[0], transparent.outputs[0], mirror.outputs[0], out)
    return m


def glass(name, ior):
    m, tree, out = material(name)
    g = tree.nodes.new("ShaderNodeBsdfGlass")
    g.distribution = "SHARP"
    g.inputs["IOR"].default_value = ior
    tree.links.new(g.outputs[0], out.inputs[0])
    return m


def one_sided_emitter(name, rgb, reflectance):
    """Mitsuba's area emitter on a shape with a diffuse BSDF: radiance on the
    front (+z) side only, where the surface also reflects as its BSDF does;
    the back is black (Mitsuba's diffuse is one-sided)."""
    m, tree, out = material(name)
    e = tree.nodes.new("ShaderNodeEmission")
    e.inputs[0].default_value = (*rgb, 1.0)
    e.inputs[1].default_value = 1.0
    d = tree.nodes.new("ShaderNodeBsdfDiffuse")
    d.inputs[0].default_value = (*reflectance, 1.0)
    d.inputs["Roughness"].default_value = 0.0
    front = tree.nodes.new("ShaderNodeAddShader")
    tree.links.new(e.outputs[0], front.inputs[0])
    tree.links.new(d.outputs[0], front.inputs[1])
    front_only(tree, front.outputs[0], out)
    return m


def place(obj, to_world, mat):
    obj.matrix_world = Y_UP @ to_world
    obj.data.materials.clear()
    obj.data.materials.append(mat)


def rectangle(to_world, mat):
    bpy.ops.mesh.primitive_plane_add(size=2)
    place(bpy.context.active_object, to_world, mat)


def vessel(name, to_world, mat):
    """celadon's OBJ OBJDIR/name.obj (y up) imported as it is, then placed
    like the sor."""
    bpy.ops.wm.obj_import(filepath=os.path.join(OBJDIR, name + ".obj"), forward_axis="Y", up_axis="Z")
    v = bpy.context.selected_objects[0]
    bpy.ops.object.shade_smooth()
    place(v, to_world, mat)


def camera(origin, target, fov_deg, fov_axis="y"):
    cam = bpy.data.cameras.new("camera")
    if fov_axis == "y":
        cam.sensor_fit = "VERTICAL"
        cam.sensor_height = 24.0
    else:
        cam.sensor_fit = "HORIZONTAL"
        cam.sensor_width = 24.0
    cam.lens = 12.0 / math.tan(math.radians(fov_deg / 2.0))
    cam.clip_start = 1e-3
    obj = bpy.data.objects.new("camera", cam)
    bpy.context.scene.collection.objects.link(obj)
    bpy.context.scene.camera = obj
    o, t = Y_UP @ Vector(origin), Y_UP @ Vector(target)
    obj.location = o
    obj.rotation_euler = (t - o).to_track_quat("-Z", "Y").to_euler()


def world(radiance):
    w = bpy.data.worlds.new("world")
    bpy.context.scene.world = w
    w.use_nodes = True
    bg = w.node_tree.nodes["Background"]
    bg.inputs[0].default_value = (radiance, radiance, radiance, 1.0)
    bg.inputs[1].default_value = 1.0


def settings(max_depth):
    sc = bpy.context.scene
    sc.render.engine = "CYCLES"
    cy = sc.cycles
    cy.device = "CPU"
    cy.samples = SPP
    cy.seed = SEED
    cy.use_adaptive_sampling = False
    cy.use_denoising = False
    # Mitsuba's max_depth counts segments from the camera (2: direct light);
    # Cycles counts bounces after the first hit (0: direct light).
    bounces = max_depth - 2
    cy.max_bounces = cy.diffuse_bounces = cy.glossy_bounces = bounces
    cy.transmission_bounces = cy.transparent_max_bounces = bounces
    cy.volume_bounces = 0
    cy.sample_clamp_direct = cy.sample_clamp_indirect = 0.0
    cy.blur_glossy = 0.0
    cy.caustics_reflective = cy.caustics_refractive = True
    cy.pixel_filter_type = "BOX"
    cy.filter_width = 1.0
    sc.render.threads_mode = "FIXED"
    sc.render.threads = 2
    sc.render.resolution_x, sc.render.resolution_y = W, H
    sc.render.resolution_percentage = 100
    sc.render.image_settings.file_format = "OPEN_EXR"
    sc.render.image_settings.color_depth = "32"
    sc.view_settings.view_transform = "Standard"
    sc.render.filepath = OUT


def studio():
    """scenes/studio/scene.xml."""
    settings(max_depth=8)
    world(0.12)
    backdrop = diffuse("backdrop", (0.62, 0.6, 0.57))
    turntable = plastic("turntable", (0.08, 0.08, 0.09), 0.2, 1.49)
    glaze = plastic("glaze", (0.5, 0.5, 0.5), 0.0, 1.54, os.path.join(SCENES, "studio", "vessel", "texture.png"))
    vessel("vessel", Matrix.Identity(4), glaze)
    # The turntable: an open cylinder y in [-0.06, 0] and a disk on top.
    bpy.ops.mesh.primitive_cylinder_add(vertices=256, radius=0.5, depth=0.06, end_fill_type="NOTHING")
    bpy.ops.object.shade_smooth()
    place(bpy.context.active_object, translate(y=-0.03) @ rotate("X", -90), turntable)
    bpy.ops.mesh.primitive_circle_add(vertices=256, radius=1.0, fill_type="NGON")
    place(bpy.context.active_object, rotate("X", -90) @ scale(0.5), turntable)
    rectangle(translate(y=-0.06) @ rotate("X", -90) @ scale(6), backdrop)
    rectangle(translate(y=2, z=-2) @ scale(6), backdrop)
    rectangle(lookat((-1.8, 2.4, 1.8), (0, 0.4, 0), (0, 1, 0)) @ scale(0.9, 0.6, 1),
              one_sided_emitter("softbox", (9, 8.6, 8), (0.5, 0.5, 0.5)))
    camera((0, 0.85, 3.3), (0, 0.45, 0), 28)


def cornell_sor():
    """scenes/cornell-sor/scene.xml."""
    settings(max_depth=10)
    world(0.0)
    white = diffuse("white", (0.8, 0.78, 0.75))
    red = diffuse("red", (0.6, 0.05, 0.05))
    green = diffuse("green", (0.1, 0.45, 0.08))
    rectangle(translate(y=-1) @ rotate("X", -90), white)
    rectangle(translate(y=1) @ rotate("X", 90), white)
    rectangle(translate(z=-1), white)
    rectangle(translate(x=-1) @ rotate("Y", 90), red)
    rectangle(translate(x=1) @ rotate("Y", -90), green)
    rectangle(translate(y=0.99) @ rotate("X", 90) @ scale(0.3, 0.25, 1),
              one_sided_emitter("light", (17, 12, 4), (0.8, 0.78, 0.75)))
    glaze = plastic("glaze", (0.5, 0.5, 0.5), 0.0, 1.54, os.path.join(SCENES, "studio", "vessel", "texture.png"))
    vessel("vessel", translate(0.15, -1, -0.25) @ rotate("Y", -30), glaze)
    # Mitsuba's dielectric defaults: BK7 (1.5046) in air (1.000277).
    bpy.ops.mesh.primitive_uv_sphere_add(segments=256, ring_count=128, radius=0.22)
    bpy.ops.object.shade_smooth()
    place(bpy.context.active_object, translate(-0.55, -0.78, 0.35), glass("glass", 1.5046 / 1.000277))
    camera((0, 0, 3.9), (0, 0, 0), 38)


def showcase():
    """scenes/showcase/scene.xml: four vessels on pedestals in closed glass
    cases with gold frames, a light panel over each case, a luminous ceiling
    and a dim constant environment."""
    settings(max_depth=8)
    world(0.06)
    wall = diffuse("wall", (0.10, 0.15, 0.19))
    pedestal = diffuse("pedestal", (0.62, 0.6, 0.57))
    glass = thin_glass("glass", 1.5 / 1.000277)
    frame = gold("frame", 0.3)
    rectangle(rotate("X", -90) @ scale(10), fresnel_plastic("floor", (0.16, 0.11, 0.08), 0.25, 1.49))
    rectangle(translate(y=2, z=-1.2) @ scale(10, 2, 1), wall)
    rectangle(translate(y=4) @ rotate("X", 90) @ scale(10),
              one_sided_emitter("ceiling", (0.45, 0.44, 0.42), (0.7, 0.7, 0.7)))
    panel = one_sided_emitter("panel", (5.5, 5.3, 4.9), (0.5, 0.5, 0.5))
    for name, x, two_sided in (("maebyeong", -1.65, False), ("bowl", -0.55, True), ("bottle", 0.55, False),
                               ("jar", 1.65, False)):
        bpy.ops.mesh.primitive_cube_add(size=2)
        place(bpy.context.active_object, translate(x=x, y=0.5) @ scale(0.28, 0.5, 0.28), pedestal)
        glaze = plastic(name, (0.5, 0.5, 0.5), 0.0, 1.54, os.path.join(SCENES, "showcase", name, "texture.png"),
                        one_sided=not two_sided)
        vessel(name, translate(x=x, y=1.0005) @ rotate("Y", 20), glaze)
        for angle, dx, dz in ((0, 0, 0.28), (180, 0, -0.28), (-90, -0.28, 0), (90, 0.28, 0)):
            rectangle(translate(x=x + dx, y=1.31, z=dz) @ rotate("Y", angle) @ scale(0.28, 0.31, 1), glass)
        rectangle(translate(x=x, y=1.62) @ rotate("X", -90) @ scale(0.28), glass)
        for dx in (-0.28, 0.28):
            for dz in (-0.28, 0.28):
                # Mitsuba's cylinder from p0 to p1, open at both ends
                bpy.ops.mesh.primitive_cylinder_add(vertices=32, radius=0.006, depth=0.62, end_fill_type="NOTHING")
                bpy.ops.object.shade_smooth()
                place(bpy.context.active_object, translate(x=x + dx, y=1.31, z=dz) @ rotate("X", -90), frame)
        rectangle(translate(x=x, y=3.98) @ rotate("X", 90) @ scale(0.5), panel)
    camera((0.25, 1.5, 3.7), (0, 1.02, 0), 60, fov_axis="x")


bpy.ops.wm.read_factory_settings(use_empty=True)
{"studio": studio, "cornell-sor": cornell_sor, "showcase": showcase}[SCENE]()
bpy.ops.render.render(write_still=True)
