"""Object > Quick Effects > Shatter Fracture: the operator and its redo panel."""

import bpy
from bpy.props import BoolProperty, EnumProperty, FloatProperty, IntProperty, StringProperty

from . import pipeline, runner, seeds
from .preferences import preferences


class OBJECT_OT_shatter_fracture(bpy.types.Operator):
    """Fracture the active mesh with shatter: exact Voronoi cells, Delaunay tetrahedra or
    plane slices, with the original's materials and UVs and an interior material"""

    bl_idname = "object.shatter_fracture"
    bl_label = "Shatter Fracture"
    bl_options = {'REGISTER', 'UNDO'}

    method: EnumProperty(
        name="Method",
        items=(
            ('VORONOI', "Voronoi", "Voronoi cells of seed points, clipped exactly to the mesh"),
            ('TETRA', "Tetra", "One fragment per Delaunay tetrahedron of surface vertices "
                               "and random points (the thesis's method)"),
            ('SLICE', "Slice", "Random planes slicing the mesh"),
        ),
        default='VORONOI')
    pattern: EnumProperty(
        name="Pattern",
        items=(
            ('UNIFORM', "Uniform", "Seeds uniform inside the mesh"),
            ('CLUSTERED', "Clustered", "Seeds around a few centres"),
            ('RADIAL', "Radial", "Dense near the impact point (the 3D cursor), coarser "
                                 "outward: glass"),
            ('SPLINTER', "Splinter", "Cells stretched along the longest axis: wood"),
        ),
        default='UNIFORM')
    source: EnumProperty(
        name="Seeds", items=seeds.SOURCES, default='PATTERN',
        description="Where the Voronoi seeds come from")
    source_limit: IntProperty(
        name="Seed Limit", default=0, min=0,
        description="At most this many seed points, drawn at random (0: all)")
    pieces: IntProperty(
        name="Pieces", default=20, min=1, soft_max=500, max=1000000,
        description="Voronoi seeds, or slicing planes")
    random_vertices: IntProperty(
        name="Random Vertices", default=50, min=0, soft_max=5000,
        description="Random points added to the surface vertices")
    skip: IntProperty(
        name="Skip", default=0, min=0,
        description="Take only every (Skip + 1)-th surface vertex")
    center: BoolProperty(name="Centre", default=False,
                         description="Also add the mesh's centre of mass")
    placement: EnumProperty(
        name="Placement",
        items=(('INTERIOR', "Interior", "Random points uniform inside the mesh"),
               ('THESIS', "Thesis", "The thesis's scheme (fills the convex hull)")),
        default='INTERIOR')
    seed: IntProperty(name="Random Seed", default=0, min=0,
                      description="The same seed gives the same fragments")
    impact_from_cursor: BoolProperty(
        name="Impact at 3D Cursor", default=True,
        description="Radial pattern: the impact point is the 3D cursor (else shatter "
                    "picks a surface point)")
    interior_material: StringProperty(
        name="Interior Material", default="",
        description="Material of the cut faces (empty: a new 'Shatter Interior')")
    keep_original: BoolProperty(
        name="Keep Original", default=True,
        description="Keep the original object (hidden); off: delete it")
    collection_name: StringProperty(
        name="Collection", default="",
        description="Collection for the fragments (empty: '<object>_fragments'); made "
                    "when missing")
    recenter: BoolProperty(name="Recenter", default=True,
                           description="Each fragment's origin at its centre of mass")
    bonds: EnumProperty(
        name="Bonds",
        items=(('NONE', "None", "No bond graph"),
               ('PROPERTIES', "Properties", "Bonded neighbours as custom properties "
                                            "(shatter_bonded, shatter_bond_area)"),
               ('CONSTRAINTS', "Rigid Body", "Rigid bodies with breakable Fixed "
                                             "constraints between bonded fragments")),
        default='PROPERTIES')
    break_threshold: FloatProperty(
        name="Break Threshold", default=500.0, min=0.0,
        description="Impulse that breaks a bond (per unit of bond area with Scale by Area)")
    scale_by_area: BoolProperty(name="Scale by Area", default=True,
                                description="Multiply the threshold by the bond's area")
    density: FloatProperty(name="Density", default=1000.0, min=1e-6,
                           description="Rigid bodies' mass = density x volume")

    @classmethod
    def poll(cls, context):
        obj = context.active_object
        return obj is not None and obj.type == 'MESH' and context.mode == 'OBJECT'

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        col = layout.column()
        col.prop(self, "method")
        if self.method == 'VORONOI':
            col.prop(self, "source")
            if self.source == 'PATTERN':
                col.prop(self, "pattern")
                col.prop(self, "pieces")
                if self.pattern == 'RADIAL':
                    col.prop(self, "impact_from_cursor")
            else:
                col.prop(self, "source_limit")
        elif self.method == 'SLICE':
            col.prop(self, "pieces")
        else:
            col.prop(self, "random_vertices")
            col.prop(self, "skip")
            col.prop(self, "center")
            col.prop(self, "placement")
        col.prop(self, "seed")
        col = layout.column()
        col.prop_search(self, "interior_material", bpy.data, "materials")
        col.prop_search(self, "collection_name", bpy.data, "collections")
        col.prop(self, "keep_original")
        col.prop(self, "recenter")
        col = layout.column()
        col.prop(self, "bonds")
        if self.bonds == 'CONSTRAINTS':
            col.prop(self, "break_threshold")
            col.prop(self, "scale_by_area")
            col.prop(self, "density")

    def build_options(self, context):
        prefs = preferences(context)
        req = runner.Request(
            method=self.method.lower(), pieces=self.pieces, pattern=self.pattern.lower(),
            random_vertices=self.random_vertices, skip=self.skip, center=self.center,
            placement=self.placement.lower(), seed=self.seed)
        return pipeline.Options(
            request=req, source=self.source, source_limit=self.source_limit,
            impact_from_cursor=self.impact_from_cursor,
            interior_material=self.interior_material, keep_original=self.keep_original,
            collection=self.collection_name, recenter=self.recenter, bonds=self.bonds,
            break_threshold=self.break_threshold, scale_by_area=self.scale_by_area,
            density=self.density, binary=prefs.shatter_path if prefs else "")

    def execute(self, context):
        wm = context.window_manager
        workspace = context.workspace

        def progress(fraction, text):
            wm.progress_update(int(100 * fraction))
            if workspace is not None:
                workspace.status_text_set("Shatter Fracture: " + text)

        wm.progress_begin(0, 100)
        try:
            outcome = pipeline.fracture_object(context, context.active_object,
                                               self.build_options(context), progress)
        except runner.ShatterError as e:
            self.report({'ERROR'}, "Shatter Fracture: %s" % e)
            return {'CANCELLED'}
        finally:
            wm.progress_end()
            if workspace is not None:
                workspace.status_text_set(None)
        for w in outcome.warnings:
            self.report({'WARNING'}, "shatter: " + w)
        r = outcome.report
        self.report({'INFO'}, "Shatter Fracture: %d fragments, %d bonds; shatter %.0f ms "
                              "(%.2f s with the process), %.2f s in all"
                    % (r["fragments"], r["bonds"], r["millis"], outcome.shatter_seconds,
                       outcome.seconds))
        return {'FINISHED'}


def menu_func(self, context):
    self.layout.operator(OBJECT_OT_shatter_fracture.bl_idname, icon='MOD_EXPLODE')
