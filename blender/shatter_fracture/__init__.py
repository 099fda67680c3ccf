"""shatter inside Blender: Object > Quick Effects > Shatter Fracture.

Exports the active mesh (modifiers applied, with its materials and UVs), runs the
`shatter` binary on it, and imports the fragments into a collection with the original's
transform and materials and an interior material on the cut faces; optionally the bond
graph as custom properties or as breakable rigid-body constraints. See blender/README.md.
"""

bl_info = {
    "name": "Shatter Fracture",
    "author": "the shatter project",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "View3D > Object > Quick Effects > Shatter Fracture",
    "description": "Exact Voronoi, tetrahedral and sliced fracture with the shatter binary",
    "doc_url": "",
    "category": "Object",
}

if "bpy" in locals():  # re-running the script reloads the modules
    import importlib

    for _name in ("runner", "objfile", "seeds", "exchange", "materials", "bonds",
                  "pipeline", "preferences", "operator"):
        if _name in locals():
            importlib.reload(locals()[_name])

import bpy

from . import bonds, exchange, materials, objfile, pipeline, preferences, runner, seeds  # noqa: F401
from . import operator

CLASSES = (preferences.ShatterFracturePreferences, operator.OBJECT_OT_shatter_fracture)


def register():
    for cls in CLASSES:
        bpy.utils.register_class(cls)
    bpy.types.VIEW3D_MT_object_quick_effects.append(operator.menu_func)


def unregister():
    bpy.types.VIEW3D_MT_object_quick_effects.remove(operator.menu_func)
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)
